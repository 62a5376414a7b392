#pragma once
// Whitted/Phong material. Colors are linear RGB.
#include <optional>

#include "core/Rgb.h"
#include "scene/CacheTechnique.h"
#include "scene/Texture.h"

namespace raycache {

// The CDCT search (Ruff's MSc thesis, 2013, Algorithm 4), in scene units. The thesis
// measured step/epsilon pairs 2/0.2, 0.4/0.05, 0.2/0.02 and 0.02/0.002 with
// depths 0..100; the defaults are its middle pair. Valid: all finite and > 0,
// epsilon < step.
// step and epsilon drive the parity search only; the improved search steps
// one texel at a time. tolerance is the improved mode's error control.
struct CdctParameters {
    float step = 0.4f;        // delta: linear-search step along the ray
    float epsilon = 0.05f;    // binary search stops once its interval is below this
    float maxDepth = 100.0f;  // misses and farther hits are stored at this distance from the centre
    // A found texel is used only if the point it stores lies within this many
    // texel footprints (at its depth) of the secondary ray; else the ray is traced.
    float tolerance = 2.0f;
};

// How an object's secondary rays are cached (honoured by the cache module).
struct CacheSettings {
    // The face resolutions a scene or the command line may ask for (the
    // memory budget may lower a cube further: RayCache::kMinBudgetResolution).
    static constexpr int kMinFaceResolution = 16;
    static constexpr int kMaxFaceResolution = 2048;
    CacheTechnique technique = CacheTechnique::None;
    int faceResolution = 512;  // texels per cube-face side, kMinFaceResolution..kMaxFaceResolution
    CdctParameters cdct;       // used when technique is Cdct or CdctParity
};

// How a surface reflects the lights: Whitted's Blinn-Phong (ambient, diffuse
// albedo * cos, specular * cos(n, h)^shininess), or glTF 2.0's
// metallic-roughness BRDF (render/MetallicRoughness.h: Lambert diffuse
// (1 - metallic) * baseColor / pi, GGX specular with height-correlated Smith
// visibility and Schlick Fresnel, no ambient), with `diffuse` (and its
// texture) as the base colour.
enum class ShadingModel { BlinnPhong, MetallicRoughness };

// Metallic-roughness surfaces smoother than this reflect as perfect mirrors
// and have no GGX lobe toward lights; rougher ones spawn no mirror ray.
inline constexpr float kSmoothRoughness = 0.1f;

struct Material {
    ShadingModel model = ShadingModel::BlinnPhong;
    float metallic = 0.0f;   // metallic-roughness only
    float roughness = 1.0f;  // metallic-roughness only: perceptual roughness, alpha = roughness^2
    Rgb emission{0.0f};      // metallic-roughness only: radiance added to the surface
    // Metallic-roughness only: Schlick's Fresnel of the dielectric base runs
    // from specularF0 (per channel, at normal incidence) to specularF90 at
    // grazing; glTF's defaults are 0.04 and 1, KHR_materials_specular's
    // factors change them (scene/PbrToBlinnPhong.h, metallicRoughnessFromPbr).
    Rgb specularF0{0.04f};
    float specularF90 = 1.0f;  // mix(specularFactor, 1, metallic): the metal's grazing F is 1
    // Metallic-roughness only, glTF's textures (linear data, not colours):
    // the metallic-roughness texture's green channel multiplies `roughness`
    // and its blue channel `metallic` at each hit; the normal texture holds
    // tangent-space normals (x, y scaled by normalScale) that replace the
    // shading normal (render/SurfaceTextures.h).
    std::optional<Texture> metallicRoughnessTexture;
    std::optional<Texture> normalTexture;
    float normalScale = 1.0f;
    Rgb ambient{0.1f};                    // ambient reflectance, multiplies the albedo
    Rgb diffuse{0.8f};                    // albedo when there is no texture
    std::optional<Texture> diffuseTexture;  // overrides `diffuse` when present
    Rgb specular{0.0f};                   // Blinn-Phong highlight color
    float shininess = 32.0f;              // Blinn-Phong exponent
    // Blinn-Phong: kr and kt, the weights of the mirror-reflected and the
    // refracted ray. Metallic-roughness: a mirror ray is spawned where
    // reflectivity > 0, and transmissivity is the share of the light the
    // base layer transmits (transmission * (1 - metallic)); each ray's
    // weight is Fresnel's at its hit (tests/render/SecondaryRayWeights.h).
    float reflectivity = 0.0f;
    float transmissivity = 0.0f;
    float ior = 1.5f;                     // index of refraction of the inside
    Rgb transmissionTint{1.0f};           // metallic-roughness only: what tints the refracted ray (baseColorFactor)
    CacheSettings cache;

    bool reflects() const { return reflectivity > 0.0f; }
    bool refracts() const { return transmissivity > 0.0f; }
    Rgb albedo(float u, float v) const { return diffuseTexture ? diffuseTexture->sample(u, v) : diffuse; }
};

}  // namespace raycache
