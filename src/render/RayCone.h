#pragma once
// The cone of rays one pixel stands for, followed along its path (ray cones:
// Akenine-Möller et al., "Texture Level of Detail Strategies for Real-Time Ray
// Tracing", Ray Tracing Gems, 2019). Multi-resolution caching cubes read it
// to know how wide a texel a lookup can take (cache/CoarseLevels.h).
#include <cmath>
#include <variant>

#include "scene/SceneObject.h"

namespace raycache {

struct RayCone {
    float width = 0.0f;   // the cone's width where the ray starts
    float spread = 0.0f;  // the angle between the ray and its neighbouring pixels' rays, radians

    // The cone of a ray leaving the surface this one hits at distance `t`,
    // of curvature `curvature` (1 / radius; 0 for a flat surface): the hit
    // footprint's normals differ by width * curvature, which turns reflected
    // directions by twice that. Refraction is given the same spread (an
    // approximation: it turns directions by less at every interface).
    RayCone bounced(float t, float curvature) const {
        const float w = std::fabs(width + spread * t);
        return {w, spread + 2.0f * w * curvature};
    }
};

// The curvature RayCone::bounced uses for a surface of `object`: 1 / radius
// for spheres; 0 for meshes, whose curvature is not known here (the cone is
// then narrower than the truth, so lookups read finer levels: never blurrier).
inline float coneCurvature(const SceneObject& object) {
    if (const auto* sphere = std::get_if<Sphere>(&object.shape))
        return sphere->radius > 0.0f ? 1.0f / sphere->radius : 0.0f;
    return 0.0f;
}

}  // namespace raycache
