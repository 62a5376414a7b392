#include "scene/PbrToBlinnPhong.h"

#include <algorithm>
#include <cmath>

namespace raycache {
namespace {

// glTF's reflectance at normal incidence of every dielectric (ior 1.5).
constexpr float kDielectricF0 = 0.04f;
constexpr float kMaxShininess = 4096.0f;
// The caching cube mirrors and glass get; --technique and --cache-resolution override it.
const CacheSettings kPbrCached{CacheTechnique::Cct, 512};

Rgb mix(const Rgb& a, const Rgb& b, float t) {
    return a * (1.0f - t) + b * t;
}

// The highlight: F0 * (1 - roughness) * (s + 8) / 8, each channel at most 1.
// (s + 8) / (8 pi) normalizes a Blinn-Phong lobe (its peak grows as it
// narrows, as a microfacet highlight's does); the pi is dropped because
// raycache's diffuse term has no 1 / pi either. (1 - roughness) fades the
// highlight out as the lobe widens to a flat one (s = 0 at roughness 1),
// which a term without the cosine of the light would show as a constant.
Rgb highlight(const Rgb& f0, float roughness, float shininess) {
    const Rgb s = f0 * ((1.0f - roughness) * (shininess + 8.0f) / 8.0f);
    return {std::min(s.r, 1.0f), std::min(s.g, 1.0f), std::min(s.b, 1.0f)};
}

// The smallest roughness anywhere on the surface: the factor, times the
// texture's smallest green value when it has one (bilinear filtering never
// goes below the smallest texel).
float smoothestRoughness(const PbrMaterial& pbr) {
    if (!pbr.metallicRoughnessTexture || pbr.metallicRoughnessTexture->pixels().empty()) return pbr.roughness;
    float smallest = 1.0f;
    for (const Rgb& texel : pbr.metallicRoughnessTexture->pixels()) smallest = std::min(smallest, texel.g);
    return pbr.roughness * smallest;
}

}  // namespace

PbrMaterialKind pbrMaterialKind(const PbrMaterial& pbr) {
    if (pbr.metallic >= 0.9f && pbr.roughness <= 0.1f) return PbrMaterialKind::Mirror;
    if (pbr.transmission * (1.0f - pbr.metallic) > 0.0f) return PbrMaterialKind::Glass;
    return PbrMaterialKind::Diffuse;
}

float blinnPhongShininess(float roughness) {
    const float alpha = roughness * roughness;
    if (!(alpha > 0.0f)) return kMaxShininess;
    const float s = 2.0f / (alpha * alpha) - 2.0f;
    return std::clamp(std::round(s), 0.0f, kMaxShininess);
}

float luminance(const Rgb& c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

Material blinnPhongFromPbr(const PbrMaterial& pbr) {
    Material m;  // ambient 0.1, as a JSON material's default
    m.shininess = blinnPhongShininess(pbr.roughness);
    Rgb albedo;  // what multiplies the base colour (and its texture)
    switch (pbrMaterialKind(pbr)) {
        case PbrMaterialKind::Mirror: {
            m.reflectivity = std::clamp(luminance(pbr.baseColor), 0.0f, 1.0f);
            // The share the mirror does not reflect scatters with the base colour:
            // what is left of a gold mirror's tint.
            albedo = pbr.baseColor * (1.0f - m.reflectivity);
            m.specular = highlight(mix(Rgb(kDielectricF0), pbr.baseColor, pbr.metallic), pbr.roughness, m.shininess);
            m.cache = kPbrCached;
            break;
        }
        case PbrMaterialKind::Glass: {
            const float transmitted = pbr.transmission * (1.0f - pbr.metallic);
            const float f0 = std::pow((pbr.ior - 1.0f) / (pbr.ior + 1.0f), 2.0f);
            m.reflectivity = f0;
            m.transmissivity = transmitted * (1.0f - f0);
            m.ior = pbr.ior;
            albedo = pbr.baseColor * (1.0f - transmitted);
            m.specular = highlight(mix(Rgb(f0), pbr.baseColor, pbr.metallic), pbr.roughness, m.shininess);
            m.cache = kPbrCached;
            break;
        }
        case PbrMaterialKind::Diffuse:
            // A metal's colour lies in its reflection: a smooth one shows it in
            // the highlight, a rough one scatters it as widely as a diffuse
            // surface does.
            albedo = pbr.baseColor * (1.0f - pbr.metallic * (1.0f - pbr.roughness));
            m.specular = highlight(mix(Rgb(kDielectricF0), pbr.baseColor, pbr.metallic), pbr.roughness, m.shininess);
            break;
    }
    m.diffuse = albedo;
    if (pbr.baseColorTexture) {
        const Rgb scale = albedo;
        std::shared_ptr<const Image> pixels = pbr.baseColorTexture;
        if (!(scale == Rgb(1.0f))) {
            auto scaled = std::make_shared<Image>(*pbr.baseColorTexture);
            for (Rgb& p : scaled->pixels()) p *= scale;
            pixels = std::move(scaled);
        }
        m.diffuseTexture = Texture::image(std::move(pixels));
    }
    return m;
}

Material metallicRoughnessFromPbr(const PbrMaterial& pbr) {
    Material m;
    m.model = ShadingModel::MetallicRoughness;
    m.ambient = Rgb(0.0f);  // Cycles with no world light has none
    m.specular = Rgb(0.0f);
    m.metallic = pbr.metallic;
    m.roughness = pbr.roughness;
    m.emission = pbr.emission;
    // KHR_materials_specular: F0 = min(0.04 * specularColorFactor, 1) *
    // specularFactor and F90 = specularFactor for the dielectric base. The
    // specification's F0 also follows the ior; Cycles' Principled BSDF (the
    // oracle, docs/scene-format.md) keeps an opaque surface's F0 apart from
    // its IOR, and so does raycache: 0.04 unless this extension says.
    const auto dielectricF0 = [&](float color) { return std::min(0.04f * color, 1.0f) * pbr.specularFactor; };
    m.specularF0 = {dielectricF0(pbr.specularColor.r), dielectricF0(pbr.specularColor.g),
                    dielectricF0(pbr.specularColor.b)};
    // mix(specularFactor, 1, metallic), written so that a factor of 1 gives 1 exactly.
    m.specularF90 = pbr.specularFactor + (1.0f - pbr.specularFactor) * pbr.metallic;
    m.ior = pbr.ior;
    const float transmitted = pbr.transmission * (1.0f - pbr.metallic);
    // The rays' weights are Fresnel's at each hit (tests/render/SecondaryRayWeights.h):
    // here only whether the rays are spawned, and the transmitted share.
    if (transmitted > 0.0f) {
        m.reflectivity = 1.0f;
        m.transmissivity = transmitted;
        m.transmissionTint = pbr.baseColor;
        m.cache = kPbrCached;
    } else if (smoothestRoughness(pbr) < kSmoothRoughness) {
        m.reflectivity = 1.0f;
        m.cache = kPbrCached;
    }
    if (pbr.metallicRoughnessTexture) m.metallicRoughnessTexture = Texture::image(pbr.metallicRoughnessTexture);
    if (pbr.normalTexture) {
        m.normalTexture = Texture::image(pbr.normalTexture);
        m.normalScale = pbr.normalScale;
    }
    const Rgb albedo = pbr.baseColor * (1.0f - transmitted);
    m.diffuse = albedo;
    if (pbr.baseColorTexture) {
        std::shared_ptr<const Image> pixels = pbr.baseColorTexture;
        if (!(albedo == Rgb(1.0f))) {
            auto scaled = std::make_shared<Image>(*pbr.baseColorTexture);
            for (Rgb& p : scaled->pixels()) p *= albedo;
            pixels = std::move(scaled);
        }
        m.diffuseTexture = Texture::image(std::move(pixels));
    }
    return m;
}

}  // namespace raycache
