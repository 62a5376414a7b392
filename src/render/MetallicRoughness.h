#pragma once
// glTF 2.0's metallic-roughness BRDF (the specification's Appendix B), the
// scalar rule that the tile kernel's lanes (render/HitLaneKernels.inc)
// follow operation for operation: Lambert diffuse (1 - metallic) *
// baseColor / pi, and GGX specular D * Vis * F with alpha = roughness^2,
// height-correlated Smith visibility and Schlick's Fresnel with F0 =
// mix(0.04, baseColor, metallic) (KHR_materials_specular changes the 0.04
// and the grazing 1: Material::specularF0, specularF90). The diffuse term
// leaves out the specification's (1 - F) factor, so that it does not depend on the view
// (the Render Cache keeps it while the eye moves). Surfaces smoother than
// kSmoothRoughness (scene/Material.h) have no specular lobe toward a light: a point light's
// reflection in them is a point, and their mirror ray, weighted by Schlick's
// Fresnel at the hit (tests/render/SecondaryRayWeights.h), carries the rest.
#include "core/Rgb.h"
#include "core/Vec3.h"
#include "scene/Material.h"

namespace raycache {

inline constexpr float kInversePi = 0.318309886183790671538f;
// The smallest cosine between the normal and the viewer that the
// visibility term divides by (an interpolated normal may face away).
inline constexpr float kMinViewCosine = 1e-4f;

// Whether the material has a GGX lobe toward lights.
inline bool hasSpecularLobe(const Material& m) { return m.roughness >= kSmoothRoughness; }

// The diffuse factor (1 - metallic) / pi that multiplies the base colour.
inline float diffuseFactor(const Material& m) { return (1.0f - m.metallic) * kInversePi; }

// F0 = mix(dielectricF0, baseColor, metallic), per channel; dielectricF0 is
// the material's specularF0 (0.04 by default).
inline float reflectanceAtNormal(float dielectricF0, float baseColor, float metallic) {
    return dielectricF0 * (1.0f - metallic) + baseColor * metallic;
}

// Schlick's Fresnel F0 + (F90 - F0) * w, w = schlickWeight(cosine).
inline float schlickFresnel(float f0, float f90, float w) { return f0 + (f90 - f0) * w; }

// (1 - cosine)^5, Schlick's weight.
inline float schlickWeight(float cosine) {
    const float x = 1.0f - cosine;
    const float x2 = x * x;
    return x2 * x2 * x;
}

// D * Vis of the GGX lobe for alpha^2 `alpha2`: D = alpha^2 / (pi (nh^2 (alpha^2 - 1) + 1)^2),
// Vis = 0.5 / (nl sqrt(nv^2 (1 - alpha^2) + alpha^2) + nv sqrt(nl^2 (1 - alpha^2) + alpha^2)).
inline float ggxLobe(float alpha2, float nDotH, float nDotL, float nDotV) {
    const float d = nDotH * nDotH * (alpha2 - 1.0f) + 1.0f;
    const float distribution = alpha2 / (3.14159265358979323846f * (d * d));
    const float oneMinus = 1.0f - alpha2;
    const float lambdaV = nDotL * std::sqrt(nDotV * nDotV * oneMinus + alpha2);
    const float lambdaL = nDotV * std::sqrt(nDotL * nDotL * oneMinus + alpha2);
    return distribution * (0.5f / (lambdaV + lambdaL));
}

// The specular BRDF value D * Vis * F for unit normal n, light direction l
// and view direction v (both away from the surface), base colour `baseColor`.
inline Rgb ggxSpecular(const Material& m, const Rgb& baseColor, const Vec3& n, const Vec3& l, const Vec3& v) {
    const Vec3 h = l + v;
    const float inverse = 1.0f / std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
    const float hx = h.x * inverse, hy = h.y * inverse, hz = h.z * inverse;
    const float cosineH = n.x * hx + n.y * hy + n.z * hz;
    const float nDotH = 0.0f < cosineH ? cosineH : 0.0f;
    const float cosineVH = v.x * hx + v.y * hy + v.z * hz;
    const float vDotH = 0.0f < cosineVH ? cosineVH : 0.0f;
    const float cosineV = n.x * v.x + n.y * v.y + n.z * v.z;
    const float nDotV = kMinViewCosine < cosineV ? cosineV : kMinViewCosine;
    const float nDotL = n.x * l.x + n.y * l.y + n.z * l.z;
    const float alpha = m.roughness * m.roughness;
    const float lobe = ggxLobe(alpha * alpha, nDotH, nDotL, nDotV);
    const float w = schlickWeight(vDotH);
    const float f0r = reflectanceAtNormal(m.specularF0.r, baseColor.r, m.metallic),
                f0g = reflectanceAtNormal(m.specularF0.g, baseColor.g, m.metallic),
                f0b = reflectanceAtNormal(m.specularF0.b, baseColor.b, m.metallic);
    return {schlickFresnel(f0r, m.specularF90, w) * lobe, schlickFresnel(f0g, m.specularF90, w) * lobe,
            schlickFresnel(f0b, m.specularF90, w) * lobe};
}

}  // namespace raycache
