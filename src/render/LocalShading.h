#pragma once
// Local shading of Whitted ray tracing (Whitted 1980): one shadow ray per
// light toward the lights that face a surface point, and what a ray that
// hits nothing sees. The shading itself (Blinn-Phong or glTF's
// metallic-roughness BRDF, render/MetallicRoughness.h) is computed in lanes
// (render/HitLanes.h), and its scalar rule, which the lanes are tested
// against, is tests/render/ScalarShadingRule.h. The rays themselves (shadow,
// reflected, refracted) are traced by the tile kernel (render/TileKernel.h),
// a whole wave at a time.
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
    float strength;   // spot-cone factor, 1 for other lights; a physical light's also its falloff (scene/Light.h)
};

// A spot light's cone: the cosines of its half-angle and of the angle where
// its falloff starts; for a physical spot, KHR_lights_punctual's
// angleScale = 1 / max(0.001, inner - outer) and angleOffset = -outer * angleScale.
struct SpotCone {
    float outer, inner;
    float angleScale = 0.0f, angleOffset = 0.0f;
};

// A physical light's falloff at distance^2 `squared` and distance
// `distance`: the range window over the squared distance (scene/Light.h).
inline float physicalFalloff(const Light& light, float squared, float distance) {
    float window = 1.0f;
    if (light.range > 0.0f) {
        const float ratio = distance / light.range;
        const float ratio2 = ratio * ratio;
        window = 1.0f - ratio2 * ratio2;
        window = window < 0.0f ? 0.0f : (1.0f < window ? 1.0f : window);
    }
    return window / squared;
}

// KHR_lights_punctual's spot factor at the cosine `cosine` of the angle to the spot's axis.
inline float physicalSpotFactor(const SpotCone& spot, float cosine) {
    float t = cosine * spot.angleScale + spot.angleOffset;
    t = t < 0.0f ? 0.0f : (1.0f < t ? 1.0f : t);
    return t * t;
}

class LocalShading {
public:
    // Throws InputError if the scene has more than kMaxLights lights.
    explicit LocalShading(const Scene& scene);

    // What a ray that hits nothing sees.
    Rgb background(const Ray& ray) const { return scene_.environment.lookup(ray.direction); }

    // Writes the shadow rays for lights that face `sp` into `out` (room for
    // one per light, at most kMaxLights) and returns how many were written.
    int shadowQueries(const SurfacePoint& sp, ShadowQuery* out) const;
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
