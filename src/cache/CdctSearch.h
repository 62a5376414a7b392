#pragma once
// The CDCT searches (Ruff's MSc thesis, 2013): find where a secondary ray leaving a cube's
// object meets the surface the cube's depths describe, relief-mapping style,
// and return the color cached there. Two variants:
//  - parity: the thesis's Algorithm 4 as specified (fixed steps delta along
//    the ray from where it leaves the box, then a binary search down to
//    epsilon; an invalid texel aborts);
//  - improved: steps of about one texel, an early exit past the farthest
//    cached surface, error control and optional depth-aware filtering
//    (docs/caching.md says why each one, docs/performance.md what each buys).
// Both are pure functions of the cube and the ray, and take a bounded number
// of steps whatever the input.
#include "cache/CachingCube.h"
#include "cache/DepthPyramid.h"
#include "core/Rgb.h"
#include "core/Vec3.h"
#include "scene/Material.h"

namespace raycache {

// The improved mode's changes, each on its own switch so it can be measured
// on its own; all on is the default `cdct` technique.
struct CdctImprovements {
    bool prefill = true;       // fill the whole cube from its centre before the first lookup
    bool texelSteps = true;    // steps of ~one texel instead of a fixed delta
    bool earlyExit = true;     // stop past the farthest cached surface: only environment lies beyond
    bool skipEmptySpace = true;  // cross blocks nearer than all their depths in one step (DepthPyramid)
    bool errorControl = true;  // reject a found texel whose point lies off the ray (parameters.tolerance)
    bool filter = true;        // depth-aware bilinear blend of the found texel's neighbours
    // Trace a ray whose found texel saw a mirror or glass from the centre:
    // its colour depends on where it is seen from (RayCache::PrefillTexel).
    bool traceViewDependent = true;
    // Trace a ray that meets the cube's own object (a concave mirror seeing
    // itself): the pre-fill sees past that surface (RayCache::seesPastOwnSurface).
    bool traceOwnSurface = true;
    // With texelSteps: walk exactly the texels the ray crosses, face by face
    // (a 2D DDA; one division per texel, no cube addressing), instead of
    // marching along the ray in turns of about a texel.
    bool faceWalk = true;
};

enum class CdctOutcome {
    Found,      // the color in `color` answers the ray
    Invalid,    // the search met an invalid texel: trace the ray
    Rejected,   // error control: the cached point is off the ray: trace the ray
    Exhausted,  // the step bound was reached (or the ray is degenerate): trace the ray
};

struct CdctResult {
    CdctOutcome outcome = CdctOutcome::Exhausted;
    Rgb color{};
    int steps = 0;  // texels of the cube the search sampled (march and bisection steps)
    int texel = -1;  // Found or Rejected: the texel the ray met (before filtering)
};

// At most this many texel-sized steps per face side of the cube (improved
// search); a ray sweeps at most half a turn as seen from the centre, about
// 3.2 face sides, so the bound only stops pathological input.
inline constexpr int kCdctTexelStepsPerSide = 4;
// Binary-search halvings, both searches.
inline constexpr int kCdctMaxBinarySteps = 64;

CdctResult searchCdctParity(const CachingCube& cube, const CdctParameters& parameters, const Vec3& origin,
                            const Vec3& direction);

// `farthestSurface`: the largest stored depth below parameters.maxDepth in
// the cube (0 if none), the early exit's bound. `pyramid`: the cube's depth
// pyramid, current with its depths, for skipping empty space (null: none).
CdctResult searchCdctImproved(const CachingCube& cube, const CdctParameters& parameters,
                              const CdctImprovements& improvements, float farthestSurface, const DepthPyramid* pyramid,
                              const Vec3& origin, const Vec3& direction);

// The ray parameter t >= 0 at which origin + t * direction (unit) is `radius`
// from `center` on the way out; 0 when the ray never gets that far inside.
float rayParameterAtDistance(const Vec3& center, const Vec3& origin, const Vec3& direction, float radius);

}  // namespace raycache
