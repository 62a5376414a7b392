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
//   - `litShadowOrigins`, `blockedShadowOrigins`: where the shadow rays start
//     (beside the shaded hits), apart for those that reached their light and
//     those something stopped, with the lights each kind went toward
//     (`litLights`, `blockedLights`); those toward a point or spot light L
//     lie inside hull(origins, L), those toward a directional light inside
//     the origins swept along it;
//   - escaped rays lie inside escapeOrigins + t * escapeDirections, t >= 0.
//
// Why the shadow rays are kept apart: a ray that reached its light crossed
// nothing, so only a changed object's new pose can stop it; a ray something
// stopped stays stopped unless what stopped it moved, so only a changed
// object's old pose can free it. Each is tested against the one pose that
// can change its answer (RegionPose). A texel shadowed by a still object
// keeps its shadow while another object passes through it; a lit texel keeps
// its light when the ray merely crosses where an object was. A light toward
// which a hit sent no shadow ray (below its horizon) cannot be changed for it
// by a moving object: only a changed light, which drops every shaded tree.
#include <cstdint>
#include <span>

#include "core/Box3.h"
#include "scene/Light.h"

namespace raycache {

// Which pose of a changed object a region bounds: where it was before the
// change, where it is after, or either (a test that does not tell them apart).
enum class RegionPose : unsigned char { Before, After, Either };

struct RayTreeBounds {
    Box3 segmentStarts, segmentEnds;
    Box3 litShadowOrigins, blockedShadowOrigins;
    std::uint64_t litLights = 0, blockedLights = 0;  // bit i: a ray toward Scene::lights[i] (kMaxLights = 64)
    Box3 escapeOrigins;
    Box3 escapeDirections;
    bool shaded = false;              // some hit was lit: depends on every light
    bool dependsOnEverything = false;  // used an answer whose dependencies are not kept (CDCT)

    bool empty() const { return segmentStarts.empty() && escapeOrigins.empty() && !shaded && !dependsOnEverything; }
    void addSegment(const Vec3& origin, const Vec3& hit) {
        segmentStarts.add(origin);
        segmentEnds.add(hit);
    }
    // A shadow ray from `origin` toward light `light` and whether it reached it.
    void addShadowRay(const Vec3& origin, int light, bool reachedLight) {
        const std::uint64_t bit = std::uint64_t{1} << light;
        if (reachedLight) {
            litShadowOrigins.add(origin);
            litLights |= bit;
        } else {
            blockedShadowOrigins.add(origin);
            blockedLights |= bit;
        }
    }
    // Shadow rays toward every light whose answers are not known here:
    // counted as both kinds.
    void addShadowRaysOfUnknownAnswer(const Vec3& origin) {
        litShadowOrigins.add(origin);
        blockedShadowOrigins.add(origin);
        litLights = blockedLights = ~std::uint64_t{0};
    }
    bool hasShadowRays() const { return !litShadowOrigins.empty() || !blockedShadowOrigins.empty(); }
    void addEscape(const Vec3& origin, const Vec3& direction) {
        escapeOrigins.add(origin);
        escapeDirections.add(direction);
    }
    void add(const RayTreeBounds& o) {
        segmentStarts.add(o.segmentStarts);
        segmentEnds.add(o.segmentEnds);
        litShadowOrigins.add(o.litShadowOrigins);
        blockedShadowOrigins.add(o.blockedShadowOrigins);
        litLights |= o.litLights;
        blockedLights |= o.blockedLights;
        escapeOrigins.add(o.escapeOrigins);
        escapeDirections.add(o.escapeDirections);
        shaded = shaded || o.shaded;
        dependsOnEverything = dependsOnEverything || o.dependsOnEverything;
    }

    // Whether a changed object inside `box` in pose `pose` may change a ray
    // of the tree: meet a traced segment or an escaped ray, or (when shaded)
    // stop a shadow ray that reached one of `lights` (pose After or Either) or
    // free one that was stopped (pose Before or Either). False only when it
    // cannot. `blockedStayBlocked`: leave the stopped shadow rays out (a
    // shape the change put there stops every one of them again:
    // blockedRaysAllMeetBall).
    bool mayMeet(const Box3& box, std::span<const Light> lights, RegionPose pose = RegionPose::Either,
                 bool blockedStayBlocked = false) const;
    // The same for a ball (a moving sphere) inside `box`: its box first, then
    // the ball itself.
    bool mayMeetBall(const Vec3& centre, float radius, const Box3& box, std::span<const Light> lights,
                     RegionPose pose = RegionPose::Either, bool blockedStayBlocked = false) const;
    // Whether every stopped shadow ray, from anywhere in
    // `blockedShadowOrigins` toward any light of `blockedLights`, meets the
    // ball (centre, radius) and no such light lies within `lightClearance`
    // of the centre: a ball that a change put there then stops them all again
    // (a shadow that a moving ball still casts stays), whatever stopped them
    // before. The points whose segment to a light meets a ball form a convex
    // set (the ball and the cone of its shadow behind it; along a
    // directional light, the ball swept against it), so the box's corners
    // decide. The caller passes a radius shrunk for rounding.
    bool blockedRaysAllMeetBall(const Vec3& centre, float radius, float lightClearance,
                                std::span<const Light> lights) const;
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
// The ball against { o + t * d : o in origins, d in directions, t >= 0 }
// (widened as boxMeetsRays is): per axis [olo + t*dlo, ohi + t*dhi], again a
// box whose corners move linearly with t. When the directions' box spans zero
// on every axis no face of the set moves away from the ball: then the answer
// is the box test's against the ball's box.
bool ballMeetsRays(const Vec3& centre, float radius, const Box3& origins, const Box3& directions);
// does `box` meet { o + t * d : o in origins, d in directions, t >= 0 }?
// (conservative: the set of rays is widened to every pairing of components)
bool boxMeetsRays(const Box3& box, const Box3& origins, const Box3& directions);

}  // namespace raycache
