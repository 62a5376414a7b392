#pragma once
// sphereRoot (trace/SphereIntersection.h) for sixteen rays at once: the
// sphere callbacks of Embree's 16-wide packets solve every lane in one pass
// instead of one lane after another. Each lane's result is bit for bit the
// scalar sphereRoot's (the same IEEE operations in the same order; tested in
// tests/trace/SphereLanesTest.cpp), so a sphere hit's distance does not
// depend on how the ray was traced.
#include "scene/SceneObject.h"

namespace raycache {

// The rays of one packet as Embree lays them out: each field an array of
// sixteen floats.
struct RayLanePointers {
    const float *originX, *originY, *originZ;
    const float *directionX, *directionY, *directionZ;
    const float *tNear, *tFar;
};

// t[k] = sphereRoot(sphere, ray k) for the lanes where active[k] is
// non-zero; -1 elsewhere. Runs the AVX-512, AVX2 or baseline x86-64 code,
// as laneLevel() decides (core/LaneLevels.h); all give the same bits.
void sphereRoots16(const Sphere& sphere, const RayLanePointers& rays, const int* active, float* t);

}  // namespace raycache
