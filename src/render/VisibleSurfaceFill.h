#pragma once
// Caching cubes filled from what the camera sees (RayCacheSettings::visibleFill,
// docs/caching.md "Filled from visible surfaces"): a ray leaving a caching
// object toward a surface point X that a camera ray already shaded this frame
// would bring back X's colour as seen from there, if nothing lies between. So
// for each such X near a CCT cube's object, a ray is aimed at X from the
// object's bounding sphere, from about where the camera's reflected rays
// toward X leave it; if one visibility ray finds nothing in between, the
// texel its direction addresses takes the pixel's colour, instead of a traced
// reflection ray with its shading and shadow rays.
//
// Exact (up to float rounding of the hit point) where X's colour does not
// depend on the direction it is seen from: surfaces that neither reflect nor
// refract and have no highlight (VisibleFill::Exact). With highlights, the
// camera's highlight is stored for a ray from elsewhere: an approximation
// (VisibleFill::Approximate). Mirrors and glass never fill: what they show
// toward the object is not what they showed the camera.
//
// The fill of a tile is queued in the tile's own store batch, after the stores
// of its traced rays (which win a texel both fill), so cubes stay identical for
// any thread count and process count.
#include <cstdint>
#include <span>
#include <vector>

#include "cache/RayCache.h"
#include "cache/VisibleFill.h"
#include "core/Rgb.h"
#include "core/Vec3.h"
#include "scene/Scene.h"
#include "trace/TraceScene.h"

namespace raycache {

// A pixel's first hit on a surface that may fill, with the pixel's colour.
struct VisiblePoint {
    Vec3 position;
    Rgb color;
};

// Per-worker buffers, reused from tile to tile.
struct VisibleFillScratch {
    struct Candidate {
        int objectId;
        int texel;
        int point;  // into the tile's points
        Ray ray;    // from the object toward the point
    };
    std::vector<Candidate> candidates;
    std::vector<Ray> rays;
    std::vector<unsigned char> occluded;
};

class VisibleSurfaceFill {
public:
    // Points farther from a cube's centre than this many times its object's
    // bounding radius do not fill it (the bound keeps the work per pixel to
    // the few cubes nearby).
    // On grid-32 at 1024², 8 radii traced 2.5 M visibility rays in the first
    // frame and 4 radii 0.36 M, for half the added answers.
    static constexpr float kReach = 4.0f;
    // Fixed-point steps toward the mirror point a ray starts from.
    static constexpr int kMirrorPointSteps = 3;

    // Inactive (fills nothing) unless `cache` has CCT cubes and asks for a fill.
    VisibleSurfaceFill(const Scene& scene, const TraceScene& tracer, const RayCache* cache);

    bool active() const { return !sources_.empty(); }
    // Whether a first hit on `material` may fill under the cache's setting.
    bool fills(const Material& material) const;
    // Queues, in `worker`'s current batch, a store for every texel of a CCT
    // cube that `points` show and that was invalid when the frame began (one
    // per texel, the first point in order that addresses it and is visible
    // from the object), seen from a camera at `eye`. Returns the visibility
    // rays traced.
    std::uint64_t fillTile(std::span<const VisiblePoint> points, const Vec3& eye, VisibleFillScratch& scratch,
                           CacheWorker& worker) const;

private:
    struct Source {
        int objectId;
        // Of a sphere around the cube's centre (the object's origin, read from
        // the cube: it follows a moving object) holding the object as the
        // scene was loaded.
        float radius;
        bool reflects;  // its cube holds reflected rays (else only refracted ones)
    };
    const TraceScene& tracer_;
    const RayCache* cache_ = nullptr;
    VisibleFill mode_ = VisibleFill::Off;
    std::vector<Source> sources_;
};

}  // namespace raycache
