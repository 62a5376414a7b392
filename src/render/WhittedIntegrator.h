#pragma once
// Whitted ray tracing (SPEC §1): Blinn-Phong local shading with one shadow ray
// per light, plus mirror reflection and refraction with total internal
// reflection, stopped by a maximum depth and a minimum path weight.
//
// shade() does everything for one hit with single rays. The pieces it is made
// of are public so the frame renderer can batch the shadow rays of a whole
// tile of primary hits into coherent packets.
#include <span>

#include "cache/RayCache.h"
#include "render/PathContext.h"
#include "core/Rgb.h"
#include "render/RenderSettings.h"
#include "render/SurfacePoint.h"
#include "scene/Scene.h"
#include "trace/TraceScene.h"

namespace raycache {

enum class SecondaryKind { Reflection, Refraction };

// One light that may reach a surface point, pending its shadow-ray answer.
struct ShadowQuery {
    Ray ray;          // from the surface toward the light, bounded at the light
    int lightIndex;   // into Scene::lights
    float strength;   // spot-cone factor, 1 for other lights
};

class WhittedIntegrator {
public:
    // With `cache`, secondary rays leaving a caching object are answered by
    // its cache when it can (CCT, SPEC §2). Throws InputError if the scene has
    // more than kMaxLights lights.
    WhittedIntegrator(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                      const RayCache* cache = nullptr);

    // Color arriving along `ray`, whose nearest hit is already known.
    // depth counts the rays on the path so far (1 for a primary ray); weight
    // is the product of kr/kt factors along it.
    Rgb shade(const Ray& ray, const TraceHit& hit, int depth, float weight, PathContext& path) const;

    // Traces `ray` and returns the color it brings back; `hitDistance`, when
    // given, receives the distance to the first hit (infinity for a miss).
    Rgb trace(const Ray& ray, SecondaryKind kind, int depth, float weight, PathContext& path,
              float* hitDistance = nullptr) const;

    // What the ray from inside object `objectId` (a caching cube's centre)
    // along `ray` sees once past the object itself: the object's own surfaces
    // are passed through. Counted as a pre-fill ray; `hitDistance` receives
    // the distance to the hit (infinity for a miss). The path goes on with
    // `depth` (of the rays that will read the cache) and weight 1.
    Rgb traceFromInside(int objectId, const Ray& ray, int depth, PathContext& path, float& hitDistance) const;

    // What a ray that hits nothing sees.
    Rgb background(const Ray& ray) const { return scene_.environment.lookup(ray.direction); }

    // Writes the shadow rays for lights that face `sp` into `out` (room for
    // one per light, at most kMaxLights) and returns how many were written.
    int shadowQueries(const SurfacePoint& sp, ShadowQuery* out) const;
    // Ambient plus the lights whose shadow rays came back unoccluded
    // (visible[i] answers queries[i]).
    Rgb directLight(const Material& material, const SurfacePoint& sp, const Vec3& toViewer,
                    std::span<const ShadowQuery> queries, std::span<const unsigned char> visible) const;
    // The same with the diffuse albedo already known (e.g. from a G-buffer).
    Rgb directLight(const Material& material, const Rgb& albedo, const SurfacePoint& sp, const Vec3& toViewer,
                    std::span<const ShadowQuery> queries, std::span<const unsigned char> visible) const;
    // Reflected and refracted light leaving `sp` (on object `objectId`)
    // toward the viewer of `ray`.
    Rgb secondaryLight(const Ray& ray, const SurfacePoint& sp, int objectId, int depth, float weight,
                       PathContext& path) const;

    const Scene& scene() const { return scene_; }

private:
    // A secondary ray leaving object `objectId` for the rest of the scene:
    // answered by the object's cache when it has one, else traced.
    Rgb leavingRay(int objectId, const Ray& ray, SecondaryKind kind, int depth, float weight,
                   PathContext& path) const;

    const Scene& scene_;
    const TraceScene& tracer_;
    RenderSettings settings_;
    const RayCache* cache_;
};

// Offset that lifts a spawned ray's origin off the surface it leaves, scaled
// with the magnitude of the coordinates so it survives float rounding.
float surfaceOffset(const Vec3& p);

}  // namespace raycache
