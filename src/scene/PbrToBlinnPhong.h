#pragma once
// The rule that turns a glTF 2.0 metallic-roughness material into
// raycache's Whitted/Blinn-Phong material (docs/scene-format.md, "glTF 2.0
// scenes", "Materials"). Three kinds: a smooth metal becomes a mirror, a
// transmissive material glass, anything else a diffuse surface with a
// highlight whose size and strength follow the roughness.
#include <memory>

#include "core/Image.h"
#include "core/Rgb.h"
#include "scene/Material.h"

namespace raycache {

// What the rule reads; the factors are glTF's, already checked to lie in
// their ranges ([0, 1]; ior > 0).
struct PbrMaterial {
    Rgb baseColor{1.0f};                            // baseColorFactor, linear rgb
    std::shared_ptr<const Image> baseColorTexture;  // linear; multiplies baseColor; null for none
    float metallic = 1.0f;                          // glTF's defaults
    float roughness = 1.0f;
    float transmission = 0.0f;  // KHR_materials_transmission's transmissionFactor
    float ior = 1.5f;           // KHR_materials_ior
    Rgb emission{0.0f};         // emissiveFactor (the metallic-roughness model shows it)
    // KHR_materials_specular (the metallic-roughness model reads them).
    float specularFactor = 1.0f;
    Rgb specularColor{1.0f};  // specularColorFactor
    // The metallic-roughness model's textures, linear data (null for none):
    // green multiplies roughness, blue metallic; tangent-space normals.
    std::shared_ptr<const Image> metallicRoughnessTexture;
    std::shared_ptr<const Image> normalTexture;
    float normalScale = 1.0f;  // normalTexture's scale
};

enum class PbrMaterialKind { Diffuse, Mirror, Glass };

// Mirror: metallic >= 0.9 and roughness <= 0.1. Otherwise glass when
// transmission * (1 - metallic) > 0. Otherwise diffuse.
PbrMaterialKind pbrMaterialKind(const PbrMaterial& pbr);

// The Blinn-Phong exponent of a roughness: with alpha = roughness^2,
// 2 / alpha^2 - 2 (Walter et al. 2007's match of a Beckmann lobe of width
// alpha), rounded to a whole number and kept within [0, 4096].
float blinnPhongShininess(float roughness);

// The Rec. 709 luminance of a linear colour: the one number a coloured
// mirror's reflectance becomes (raycache's kr is not a colour).
float luminance(const Rgb& c);

// The material, with base colour texture (scaled by what multiplies the
// albedo) as its diffuse texture. Mirrors and glass cache their secondary
// rays with CCT at 512² unless the command line chooses otherwise.
Material blinnPhongFromPbr(const PbrMaterial& pbr);

// The material under glTF's own BRDF (ShadingModel::MetallicRoughness): the
// base colour (times 1 - transmission) as its albedo, its texture unscaled
// when the factor is white, emission as given, no ambient, the
// metallic-roughness and normal textures as given. Its secondary rays:
// smooth surfaces (roughness < kSmoothRoughness, somewhere on the
// metallic-roughness texture if there is one) and glass reflect a mirror ray
// (reflectivity 1), glass also refracts (transmissivity transmission * (1 -
// metallic), with the metallic factor, tinted by baseColorFactor); what each
// ray weighs is Fresnel's at its hit (tests/render/SecondaryRayWeights.h).
Material metallicRoughnessFromPbr(const PbrMaterial& pbr);

}  // namespace raycache
