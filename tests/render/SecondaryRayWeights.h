#pragma once
// What a hit's mirror-reflected and refracted rays weigh in its colour, per
// channel: the scalar rule that the tile kernel's lanes
// (src/render/HitLaneKernels.inc, secondaryRayLanes) follow operation for
// operation. It lives with the tests, which hold the lanes to it; the
// renderer computes the weights in lanes only.
//
// Blinn-Phong (Whitted): the material's constants kr and kt, kt added to kr
// where the light is totally reflected.
//
// Metallic-roughness (glTF 2.0's BRDF, render/MetallicRoughness.h, in the
// limit of a smooth surface, whose specular lobe is the mirror direction and
// whose half vector is the normal):
//   - opaque: the mirror ray weighs Schlick's Fresnel at the hit's angle,
//     F = F0 + (1 - F0)(1 - cos θ)^5 with F0 = mix(0.04, baseColor,
//     metallic) per channel: a metal's reflection is tinted by its colour;
//   - glass (KHR_materials_transmission, KHR_materials_ior): the exact
//     unpolarised dielectric Fresnel F of the ior, entering or leaving
//     (core/Optics.h); the reflected ray weighs F, the refracted ray
//     (1 - F) * transmission * (1 - metallic) * baseColorFactor
//     (Material::transmissionTint); beyond the critical angle F is 1 and
//     nothing is refracted. A metallic factor on glass only lowers its
//     transmission: its reflection stays the dielectric's, untinted.
// The specification's fresnel_mix also weighs the base layer (the diffuse
// term) by 1 - F; raycache's diffuse term leaves that factor out, as
// Cycles' Principled BSDF (Blender 3.x) does, so that it stays independent
// of the view (render/MetallicRoughness.h).
// θ is the angle between the incident ray and the shading normal; an
// interpolated normal may face away from the ray, so its cosine is taken
// as |cos θ|, at most 1.
#include <cmath>

#include "core/Optics.h"
#include "core/Rgb.h"
#include "render/MetallicRoughness.h"
#include "scene/Material.h"

namespace raycache {

struct SecondaryRayWeights {
    Rgb reflected;            // the mirror-reflected ray's weight
    Rgb refracted;            // the refracted ray's weight (zero when none is refracted)
    bool totalInternal = false;  // a refracting material that reflects all the light here
};

// The weights at a hit of `material` whose albedo (the metallic-roughness
// base colour) is `albedo`, hit at cos θ = `cosI` (-dot(direction,
// normal)) from outside (`frontFace`) or inside (objects do not nest).
inline SecondaryRayWeights secondaryRayWeights(const Material& material, const Rgb& albedo, float cosI,
                                               bool frontFace) {
    SecondaryRayWeights out;
    // Entering: air -> material; leaving: material -> air.
    const float eta = frontFace ? 1.0f / material.ior : material.ior;
    const float cos2T = 1.0f - eta * eta * (1.0f - cosI * cosI);
    if (material.model != ShadingModel::MetallicRoughness) {
        float reflect = material.reflectivity;
        if (material.refracts()) {
            if (cos2T < 0.0f) {
                out.totalInternal = true;
                reflect = reflect + material.transmissivity;
            } else {
                out.refracted = Rgb(material.transmissivity);
            }
        }
        out.reflected = Rgb(reflect);
        return out;
    }
    const float absolute = std::fabs(cosI);
    const float cosine = absolute < 1.0f ? absolute : 1.0f;
    if (!material.refracts()) {
        const float w = schlickWeight(cosine);
        const float f0r = reflectanceAtNormal(material.specularF0.r, albedo.r, material.metallic),
                    f0g = reflectanceAtNormal(material.specularF0.g, albedo.g, material.metallic),
                    f0b = reflectanceAtNormal(material.specularF0.b, albedo.b, material.metallic);
        const float f90 = material.specularF90;
        out.reflected = {schlickFresnel(f0r, f90, w), schlickFresnel(f0g, f90, w), schlickFresnel(f0b, f90, w)};
        return out;
    }
    out.totalInternal = cos2T < 0.0f;
    const float cosT = std::sqrt(out.totalInternal ? 0.0f : cos2T);
    const float fresnel = dielectricFresnel(cosine, cosT, eta).unpolarised();
    // Total internal reflection, and grazing incidence at an ior of 1 (0 / 0): all reflected.
    const float reflected = out.totalInternal || !(eta * cosine + cosT > 0.0f) ? 1.0f : fresnel;
    out.reflected = Rgb(reflected);
    if (!out.totalInternal) {
        const float transmitted = (1.0f - reflected) * material.transmissivity;
        out.refracted = {material.transmissionTint.r * transmitted, material.transmissionTint.g * transmitted,
                         material.transmissionTint.b * transmitted};
    }
    return out;
}

}  // namespace raycache
