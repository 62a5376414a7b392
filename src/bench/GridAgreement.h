#pragma once
// How the grids' answers compare with Embree's for one frame (docs/grids.md,
// "Exactness"): the camera rays of every pixel and the shadow rays of their
// hits, traced by a grids tracer and by an Embree tracer over the same scene,
// and optionally by brute force (every primitive, the grids' own tests and
// tie rule), which the grids must equal bit for bit.
#include <cstdint>

#include "core/Parallel.h"
#include "scene/Camera.h"
#include "scene/Scene.h"

namespace raycache {

struct PrimaryAgreement {
    std::uint64_t rays = 0;
    std::uint64_t same = 0;        // same object and primitive (distance within 1e-5 relative), or both miss
    std::uint64_t ties = 0;        // different primitives at distances within 1e-5 relative of each other
    // The answers differ and the nearer hit is at a triangle edge (barycentric < 1e-4): the other tracer
    // slipped through the edge, to a miss or to what lies behind.
    std::uint64_t edgeGrazes = 0;
    std::uint64_t mismatches = 0;  // anything else
    std::uint64_t refused = 0;     // rays the grids handed to Embree
};

struct ShadowAgreement {
    std::uint64_t rays = 0;
    std::uint64_t same = 0;
    std::uint64_t edgeGrazes = 0;  // answers differ, and every occluder the grids' test sees is met at an edge
    std::uint64_t mismatches = 0;
    std::uint64_t refused = 0;
};

struct GridAgreement {
    PrimaryAgreement primary;
    ShadowAgreement shadow;
    bool bruteForceChecked = false;
    std::uint64_t bruteForceDifferences = 0;  // grids vs brute force, primary and shadow rays: must be 0
    int lightsWithSixFaces = 0;
};

// Traces the frame `camera` sees at width x height both ways. Brute force
// only when `bruteForce` is set (cost: rays x primitives).
GridAgreement compareGridsWithEmbree(const Scene& scene, const Camera& camera, int width, int height,
                                     const Parallel& parallel, bool bruteForce);

}  // namespace raycache
