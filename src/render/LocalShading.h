#pragma once
// Local shading of Whitted ray tracing (Whitted 1980): Blinn-Phong with one shadow
// ray per light, and what a ray that hits nothing sees. The rays themselves
// (shadow, reflected, refracted) are traced by the tile kernel
// (render/TileKernel.h), a whole wave at a time.
#include <cstdint>
#include <span>
#include <vector>

#include "core/Rgb.h"
#include "render/SurfacePoint.h"
#include "scene/Scene.h"

namespace raycache {

// One light that may reach a surface point, pending its shadow-ray answer.
struct ShadowQuery {
    Ray ray;          // from the surface toward the light, bounded at the light
    int lightIndex;   // into Scene::lights
    float strength;   // spot-cone factor, 1 for other lights
};

// A spot light's cone: the cosines of its half-angle and of the angle where
// its falloff starts.
struct SpotCone {
    float outer, inner;
};

class LocalShading {
public:
    // Throws InputError if the scene has more than kMaxLights lights.
    explicit LocalShading(const Scene& scene);

    // What a ray that hits nothing sees.
    Rgb background(const Ray& ray) const { return scene_.environment.lookup(ray.direction); }

    // Writes the shadow rays for lights that face `sp` into `out` (room for
    // one per light, at most kMaxLights) and returns how many were written.
    int shadowQueries(const SurfacePoint& sp, ShadowQuery* out) const;
    // Ambient plus the lights whose shadow rays came back unoccluded
    // (occluded[i] answers queries[i]), with the diffuse albedo at the point.
    Rgb directLight(const Material& material, const Rgb& albedo, const SurfacePoint& sp, const Vec3& toViewer,
                    std::span<const ShadowQuery> queries, std::span<const unsigned char> occluded) const;
    // directLight split in two for the Render Cache (rendercache/), which
    // keeps the first part of a sample and shades the second again when the
    // eye moves. The first: ambient plus the diffuse term of the unoccluded
    // lights; bit l of `litMask` is set for every such light l.
    Rgb viewIndependentLight(const Material& material, const Rgb& albedo, const SurfacePoint& sp,
                             std::span<const ShadowQuery> queries, std::span<const unsigned char> occluded,
                             std::uint64_t& litMask) const;
    // The second: the highlights of the lights in `litMask` seen from
    // `toViewer` (queries as shadowQueries(sp) writes them).
    Rgb highlights(const Material& material, const SurfacePoint& sp, const Vec3& toViewer,
                   std::span<const ShadowQuery> queries, std::uint64_t litMask) const;

    const Scene& scene() const { return scene_; }
    // Each light's cone (for spot lights), as shadowQueries uses it.
    std::span<const SpotCone> spotCones() const { return spotCosines_; }

private:
    const Scene& scene_;
    std::vector<SpotCone> spotCosines_;  // per light
};

// Offset that lifts a spawned ray's origin off the surface it leaves, scaled
// with the magnitude of the coordinates so it survives float rounding.
float surfaceOffset(const Vec3& p);

}  // namespace raycache
