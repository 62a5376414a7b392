#include "cache/RayTreeBounds.h"

#include <cmath>
#include <limits>

namespace raycache {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The interval of a parameter s that the two constraints below leave, narrowed
// one linear inequality at a time; empty once lo > hi.
struct ParameterRange {
    double lo, hi;
    // Keeps the s with a * s <= b.
    // Comparisons, not std::fmin/fmax (calls into libm, about 1 % of an
    // animated CCT frame); a NaN bound is ignored either way.
    void keepAtMost(double a, double b) {
        if (a > 0.0) {
            const double bound = b / a;
            if (bound < hi) hi = bound;
        } else if (a < 0.0) {
            const double bound = b / a;
            if (bound > lo) lo = bound;
        } else if (b < 0.0) {  // 0 <= b fails for every s: empty for good (lo only grows, hi only shrinks)
            lo = 1.0;
            hi = 0.0;
        }
    }
    // Keeps the s with a * s >= b.
    void keepAtLeast(double a, double b) { keepAtMost(-a, -b); }
    bool empty() const { return !(lo <= hi); }
};

}  // namespace

// A point x of the hull is apex + s * (p - apex) with p in `points` and s in
// [0, 1]. Boxes are products of intervals, so for a fixed s the question
// splits per axis: [s*a, s*b] (a, b: the points' interval minus the apex)
// must meet [c, d] (the box's interval minus the apex), i.e. s*a <= d and
// s*b >= c. Each is linear in s: the s that work form one interval, and the
// box meets the hull exactly when the three axes' intervals and [0, 1] share
// a point. Computed in double so the float inputs' rounding cannot flip it.
bool boxMeetsHull(const Box3& box, const Box3& points, const Vec3& apex) {
    if (box.empty() || points.empty()) return false;
    ParameterRange s{0.0, 1.0};
    for (int axis = 0; axis < 3; ++axis) {
        const double a = static_cast<double>(points.lo[axis]) - apex[axis];
        const double b = static_cast<double>(points.hi[axis]) - apex[axis];
        const double c = static_cast<double>(box.lo[axis]) - apex[axis];
        const double d = static_cast<double>(box.hi[axis]) - apex[axis];
        s.keepAtMost(a, d);
        s.keepAtLeast(b, c);
        if (s.empty()) return false;
    }
    return true;
}

// A point of the hull is (1-s)*a + s*b with a in `starts`, b in `ends`, s in
// [0, 1]; per axis that covers [(1-s)*slo + s*elo, (1-s)*shi + s*ehi], which
// meets [c, d] when s*(elo - slo) <= d - slo and s*(ehi - shi) >= c - shi.
bool boxMeetsSegments(const Box3& box, const Box3& starts, const Box3& ends) {
    if (box.empty() || starts.empty() || ends.empty()) return false;
    ParameterRange s{0.0, 1.0};
    for (int axis = 0; axis < 3; ++axis) {
        const double slo = starts.lo[axis], shi = starts.hi[axis];
        s.keepAtMost(static_cast<double>(ends.lo[axis]) - slo, static_cast<double>(box.hi[axis]) - slo);
        s.keepAtLeast(static_cast<double>(ends.hi[axis]) - shi, static_cast<double>(box.lo[axis]) - shi);
        if (s.empty()) return false;
    }
    return true;
}

// x = p + t * u: per axis [lo + t*u, hi + t*u] must meet [c, d]:
// t*u <= d - lo and t*u >= c - hi, for some t >= 0 shared by the axes.
bool boxMeetsSweep(const Box3& box, const Box3& points, const Vec3& direction) {
    if (box.empty() || points.empty()) return false;
    ParameterRange t{0.0, kInfinity};
    for (int axis = 0; axis < 3; ++axis) {
        const double u = direction[axis];
        t.keepAtMost(u, static_cast<double>(box.hi[axis]) - points.lo[axis]);
        t.keepAtLeast(u, static_cast<double>(box.lo[axis]) - points.hi[axis]);
        if (t.empty()) return false;
    }
    return true;
}

// For t >= 0, o + t*d over o in [olo, ohi] and d in [dlo, dhi] covers exactly
// [olo + t*dlo, ohi + t*dhi] on each axis; it meets [c, d'] when
// t*dlo <= d' - olo and t*dhi >= c - ohi.
bool boxMeetsRays(const Box3& box, const Box3& origins, const Box3& directions) {
    if (box.empty() || origins.empty() || directions.empty()) return false;
    ParameterRange t{0.0, kInfinity};
    for (int axis = 0; axis < 3; ++axis) {
        t.keepAtMost(directions.lo[axis], static_cast<double>(box.hi[axis]) - origins.lo[axis]);
        t.keepAtLeast(directions.hi[axis], static_cast<double>(box.lo[axis]) - origins.hi[axis]);
        if (t.empty()) return false;
    }
    return true;
}

bool RayTreeBounds::mayMeet(const Box3& box, std::span<const Light> lights) const {
    if (dependsOnEverything) return true;
    if (box.empty()) return false;
    if (boxMeetsSegments(box, segmentStarts, segmentEnds)) return true;
    if (boxMeetsRays(box, escapeOrigins, escapeDirections)) return true;
    if (!shaded) return false;
    for (const Light& light : lights) {
        const bool meets = light.type == LightType::Directional
                               ? boxMeetsSweep(box, shadowOrigins, -light.direction)
                               : boxMeetsHull(box, shadowOrigins, light.position);
        if (meets) return true;
    }
    return false;
}

}  // namespace raycache
