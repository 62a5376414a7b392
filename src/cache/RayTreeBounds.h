#pragma once
// What a cached colour depends on, in space: the bounds of the ray tree that
// computed it (docs/dynamic-scenes.md, "Which texels a change reaches").
//
// A texel's colour is the sum over a tree of rays: traced segments (origin to
// hit), rays that escaped to the environment, shadow rays from every shaded
// hit toward every light, and the answers of other cubes' texels. The colour
// can only change when a changed object's old or new shape meets one of those
// rays, or when a light used for shading changed. The bounds keep just enough
// to decide that conservatively (never missing a change) in a few dozen flops:
//   - `segmentStarts`, `segmentEnds`: every traced ray's origin and hit; a
//     segment from a start to an end lies in the convex hull of the two boxes
//     (a thin slab when a block's rays go from one mirror to one wall, where
//     one box around both would be large);
//   - `shadowOrigins`: where the shadow rays start (beside the shaded hits);
//     those toward a point or spot light L lie inside hull(shadowOrigins, L),
//     those toward a directional light inside shadowOrigins swept along it;
//   - escaped rays lie inside escapeOrigins + t * escapeDirections, t >= 0.
#include <span>

#include "core/Box3.h"
#include "scene/Light.h"

namespace raycache {

struct RayTreeBounds {
    Box3 segmentStarts, segmentEnds;
    Box3 shadowOrigins;
    Box3 escapeOrigins;
    Box3 escapeDirections;
    bool shaded = false;              // some hit was lit: depends on every light
    bool dependsOnEverything = false;  // used an answer whose dependencies are not kept (CDCT)

    bool empty() const { return segmentStarts.empty() && escapeOrigins.empty() && !shaded && !dependsOnEverything; }
    void addSegment(const Vec3& origin, const Vec3& hit) {
        segmentStarts.add(origin);
        segmentEnds.add(hit);
    }
    void addEscape(const Vec3& origin, const Vec3& direction) {
        escapeOrigins.add(origin);
        escapeDirections.add(direction);
    }
    void add(const RayTreeBounds& o) {
        segmentStarts.add(o.segmentStarts);
        segmentEnds.add(o.segmentEnds);
        shadowOrigins.add(o.shadowOrigins);
        escapeOrigins.add(o.escapeOrigins);
        escapeDirections.add(o.escapeDirections);
        shaded = shaded || o.shaded;
        dependsOnEverything = dependsOnEverything || o.dependsOnEverything;
    }

    // Whether a shape inside `box` may meet a ray of the tree: a traced
    // segment, an escaped ray, or (when shaded) a shadow ray toward one of
    // `lights`. False only when no such ray can touch the box.
    bool mayMeet(const Box3& box, std::span<const Light> lights) const;
    // The same for a ball (a moving sphere) inside `box`: its box first, then
    // the ball itself for the traced segments and the shadow rays (escaped
    // rays keep the box test).
    bool mayMeetBall(const Vec3& centre, float radius, const Box3& box, std::span<const Light> lights) const;
};

// The exact tests mayMeet is made of (exposed for tests):
// does `box` meet the convex hull of boxes `starts` and `ends`?
bool boxMeetsSegments(const Box3& box, const Box3& starts, const Box3& ends);
// does `box` meet the convex hull of box `points` and point `apex`?
bool boxMeetsHull(const Box3& box, const Box3& points, const Vec3& apex);
// does `box` meet { p + t * direction : p in points, t >= 0 }?
bool boxMeetsSweep(const Box3& box, const Box3& points, const Vec3& direction);
// The ball (centre, radius) against the same sets. Each set is, for one
// parameter s, a box K(s) whose corners move linearly with s, and the
// distance from the centre to K(s) is convex in s (the sets are convex
// together with s), so its minimum is found by a golden-section search;
// a hair of slack keeps the answer conservative.
bool ballMeetsHull(const Vec3& centre, float radius, const Box3& points, const Vec3& apex);
bool ballMeetsSegments(const Vec3& centre, float radius, const Box3& starts, const Box3& ends);
bool ballMeetsSweep(const Vec3& centre, float radius, const Box3& points, const Vec3& direction);
// does `box` meet { o + t * d : o in origins, d in directions, t >= 0 }?
// (conservative: the set of rays is widened to every pairing of components)
bool boxMeetsRays(const Box3& box, const Box3& origins, const Box3& directions);

}  // namespace raycache
