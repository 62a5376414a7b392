#pragma once
// Whitted/Phong material. Colors are linear RGB.
#include <optional>

#include "core/Rgb.h"
#include "scene/Texture.h"

namespace raycache {

enum class CacheTechnique { None, Cct, Cdct };

// How an object's secondary rays are cached (honoured by the cache module).
struct CacheSettings {
    CacheTechnique technique = CacheTechnique::None;
    int faceResolution = 512;  // texels per cube-face side
};

struct Material {
    Rgb ambient{0.1f};                    // ambient reflectance, multiplies the albedo
    Rgb diffuse{0.8f};                    // albedo when there is no texture
    std::optional<Texture> diffuseTexture;  // overrides `diffuse` when present
    Rgb specular{0.0f};                   // Blinn-Phong highlight color
    float shininess = 32.0f;              // Blinn-Phong exponent
    float reflectivity = 0.0f;            // kr, weight of the mirror-reflected ray
    float transmissivity = 0.0f;          // kt, weight of the refracted ray
    float ior = 1.5f;                     // index of refraction of the inside
    CacheSettings cache;

    bool reflects() const { return reflectivity > 0.0f; }
    bool refracts() const { return transmissivity > 0.0f; }
    Rgb albedo(float u, float v) const { return diffuseTexture ? diffuseTexture->sample(u, v) : diffuse; }
};

}  // namespace raycache
