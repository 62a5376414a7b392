#pragma once
// The scalar rule of local shading, one surface point at a time: the
// specification the lane kernels (render/HitLanes.h) are tested against, bit
// for bit. Ambient (Blinn-Phong) or emission (metallic-roughness) plus, for
// each light whose shadow ray came back unoccluded, its diffuse term and
// highlight, in the lanes' order of operations.
#include <algorithm>
#include <cstdint>
#include <span>

#include "render/LocalShading.h"
#include "render/MetallicRoughness.h"
#include "render/SpecularPower.h"

namespace raycache {

// The whole of it: occluded[i] answers queries[i] (as
// LocalShading::shadowQueries writes them), `albedo` is the diffuse albedo
// at the point.
inline Rgb scalarDirectLight(const LocalShading& shading, const Material& material, const Rgb& albedo,
                             const SurfacePoint& sp, const Vec3& toViewer, std::span<const ShadowQuery> queries,
                             std::span<const unsigned char> occluded) {
    const Scene& scene = shading.scene();
    if (material.model == ShadingModel::MetallicRoughness) {
        // The lanes' order (HitLaneKernels.inc, metallicRoughnessLightLanes).
        Rgb color = material.emission;
        const Rgb diffuse = albedo * diffuseFactor(material);
        const bool lobe = hasSpecularLobe(material);
        for (std::size_t q = 0; q < queries.size(); ++q) {
            if (occluded[q]) continue;
            const ShadowQuery& query = queries[q];
            const Vec3& toLight = query.ray.direction;
            Rgb lit = diffuse;
            if (lobe) lit += ggxSpecular(material, albedo, sp.normal, toLight, toViewer);
            lit *= dot(sp.normal, toLight);
            color += lit * scene.lights[static_cast<std::size_t>(query.lightIndex)].intensity * query.strength;
        }
        return color;
    }
    Rgb color = material.ambient * albedo;
    for (std::size_t q = 0; q < queries.size(); ++q) {
        if (occluded[q]) continue;
        const ShadowQuery& query = queries[q];
        const Vec3& toLight = query.ray.direction;
        Rgb lit = albedo * dot(sp.normal, toLight);
        if (!material.specular.isBlack()) {
            const float nDotH = std::max(0.0f, dot(sp.normal, normalize(toLight + toViewer)));
            lit += material.specular * specularPower(nDotH, material.shininess);
        }
        color += lit * scene.lights[static_cast<std::size_t>(query.lightIndex)].intensity * query.strength;
    }
    return color;
}

// scalarDirectLight split in two, as the Render Cache keeps the first part of
// a sample and shades the second again when the eye moves. The first:
// ambient plus the diffuse term of the unoccluded lights; bit l of `litMask`
// is set for every such light l.
inline Rgb scalarViewIndependentLight(const LocalShading& shading, const Material& material, const Rgb& albedo,
                                      const SurfacePoint& sp, std::span<const ShadowQuery> queries,
                                      std::span<const unsigned char> occluded, std::uint64_t& litMask) {
    const Scene& scene = shading.scene();
    static_assert(kMaxLights <= 64, "one bit per light");
    const bool physical = material.model == ShadingModel::MetallicRoughness;
    Rgb color = physical ? material.emission : material.ambient * albedo;
    const Rgb diffuse = physical ? albedo * diffuseFactor(material) : albedo;
    litMask = 0;
    for (std::size_t q = 0; q < queries.size(); ++q) {
        if (occluded[q]) continue;
        const ShadowQuery& query = queries[q];
        litMask |= std::uint64_t{1} << query.lightIndex;
        color += diffuse * dot(sp.normal, query.ray.direction) *
                 scene.lights[static_cast<std::size_t>(query.lightIndex)].intensity * query.strength;
    }
    return color;
}

// The second: the highlights of the lights in `litMask` seen from
// `toViewer`; `albedo` is the base colour that tints a metallic-roughness
// metal's highlight.
inline Rgb scalarHighlights(const LocalShading& shading, const Material& material, const Rgb& albedo,
                            const SurfacePoint& sp, const Vec3& toViewer, std::span<const ShadowQuery> queries,
                            std::uint64_t litMask) {
    const Scene& scene = shading.scene();
    Rgb color;
    if (material.model == ShadingModel::MetallicRoughness) {
        if (!hasSpecularLobe(material)) return color;
        for (const ShadowQuery& query : queries) {
            if (!(litMask >> query.lightIndex & 1u)) continue;
            const Vec3& toLight = query.ray.direction;
            color += ggxSpecular(material, albedo, sp.normal, toLight, toViewer) * dot(sp.normal, toLight) *
                     scene.lights[static_cast<std::size_t>(query.lightIndex)].intensity * query.strength;
        }
        return color;
    }
    if (material.specular.isBlack()) return color;
    for (const ShadowQuery& query : queries) {
        if (!(litMask >> query.lightIndex & 1u)) continue;
        const float nDotH = std::max(0.0f, dot(sp.normal, normalize(query.ray.direction + toViewer)));
        color += material.specular * specularPower(nDotH, material.shininess) *
                 scene.lights[static_cast<std::size_t>(query.lightIndex)].intensity * query.strength;
    }
    return color;
}

}  // namespace raycache
