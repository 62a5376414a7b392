#include "cache/RayTreeBounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace raycache {

namespace {

constexpr float kBoundsInfinity = std::numeric_limits<float>::infinity();

// The interval of a parameter s that the two constraints below leave, narrowed
// one linear inequality at a time; empty once lo > hi.
struct ParameterRange {
    double lo, hi;
    // Keeps the s with a * s <= b.
    // Comparisons, not std::fmin/fmax (calls into libm, measurable in an
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
    ParameterRange t{0.0, kBoundsInfinity};
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
    ParameterRange t{0.0, kBoundsInfinity};
    for (int axis = 0; axis < 3; ++axis) {
        t.keepAtMost(directions.lo[axis], static_cast<double>(box.hi[axis]) - origins.lo[axis]);
        t.keepAtLeast(directions.hi[axis], static_cast<double>(box.lo[axis]) - origins.hi[axis]);
        if (t.empty()) return false;
    }
    return true;
}

namespace {

// Smallest distance from `c` to the box with corners lo + s*dlo, hi + s*dhi
// over s in [0, sMax] (convex in s: golden-section search), compared with
// `radius` plus a slack for the search's tolerance and float rounding.
bool ballMeetsMovingBox(const Vec3& c, double radius, const Vec3& lo, const Vec3& dlo, const Vec3& hi,
                        const Vec3& dhi, double sMax) {
    const auto distance2 = [&](double s) {
        double sum = 0.0;
        for (int a = 0; a < 3; ++a) {
            const double l = lo[a] + s * dlo[a], h = hi[a] + s * dhi[a];
            const double gap = c[a] < l ? l - c[a] : c[a] > h ? c[a] - h : 0.0;
            sum += gap * gap;
        }
        return sum;
    };
    constexpr double kInverseGolden = 0.6180339887498949;
    double a = 0.0, b = sMax;
    double x1 = b - kInverseGolden * (b - a), x2 = a + kInverseGolden * (b - a);
    double f1 = distance2(x1), f2 = distance2(x2);
    for (int i = 0; i < 60 && b - a > 1e-12 * (1.0 + sMax); ++i) {
        if (f1 <= f2) {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - kInverseGolden * (b - a);
            f1 = distance2(x1);
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + kInverseGolden * (b - a);
            f2 = distance2(x2);
        }
    }
    const double nearest = std::min({f1, f2, distance2(0.0), distance2(sMax)});
    // The distance changes by at most |(dlo, dhi)| per unit of s: the interval
    // left, plus float rounding of the inputs, bounds what the search missed.
    double speed = 0.0;
    for (int k = 0; k < 3; ++k)
        speed = std::max({speed, static_cast<double>(std::fabs(dlo[k])), static_cast<double>(std::fabs(dhi[k]))});
    const double slack = 1e-6 * (1.0 + radius + std::sqrt(3.0) * speed * sMax) + std::sqrt(3.0) * speed * (b - a);
    return nearest <= (radius + slack) * (radius + slack);
}

}  // namespace

bool ballMeetsHull(const Vec3& centre, float radius, const Box3& points, const Vec3& apex) {
    if (points.empty()) return false;
    // (1 - s) * points + s * apex: corners move from the box's to the apex.
    return ballMeetsMovingBox(centre, radius, points.lo, apex - points.lo, points.hi, apex - points.hi, 1.0);
}

bool ballMeetsSegments(const Vec3& centre, float radius, const Box3& starts, const Box3& ends) {
    if (starts.empty() || ends.empty()) return false;
    return ballMeetsMovingBox(centre, radius, starts.lo, ends.lo - starts.lo, starts.hi, ends.hi - starts.hi, 1.0);
}

bool ballMeetsSweep(const Vec3& centre, float radius, const Box3& points, const Vec3& direction) {
    if (points.empty()) return false;
    const double speed = length(direction);
    if (!(speed > 0.0)) return ballMeetsMovingBox(centre, radius, points.lo, {}, points.hi, {}, 0.0);
    // Past this parameter the box is farther from the centre than the radius.
    const Vec3 middle = (points.lo + points.hi) * 0.5f;
    const double reach = (length(centre - middle) + 0.5 * length(points.hi - points.lo) + radius) / speed + 1.0;
    return ballMeetsMovingBox(centre, radius, points.lo, direction, points.hi, direction, reach);
}

bool ballMeetsRays(const Vec3& centre, float radius, const Box3& origins, const Box3& directions) {
    if (origins.empty() || directions.empty()) return false;
    // Past the smallest such t one face of the box has left the ball behind:
    // an axis whose directions all point one way moves that face away.
    double reach = kBoundsInfinity;
    for (int a = 0; a < 3; ++a) {
        if (directions.lo[a] > 0.0f)
            reach = std::min(reach, (static_cast<double>(centre[a]) + radius - origins.lo[a]) / directions.lo[a]);
        if (directions.hi[a] < 0.0f)
            reach = std::min(reach, (static_cast<double>(origins.hi[a]) - (centre[a] - radius)) / -directions.hi[a]);
    }
    if (reach == kBoundsInfinity) return boxMeetsRays(Box3{centre - Vec3{radius, radius, radius}, centre + Vec3{radius, radius, radius}},
                                                 origins, directions);
    return ballMeetsMovingBox(centre, radius, origins.lo, directions.lo, origins.hi, directions.hi,
                              std::max(reach, 0.0) + 1.0);
}

namespace {

// The shadow rays whose answer a changed object in pose `pose` can change
// (RayTreeBounds.h): `meets(origins, light)` for the rays that reached their
// light against the new pose, for the stopped ones against the old.
template <typename Meets>
bool shadowRayMayChange(const RayTreeBounds& bounds, std::span<const Light> lights, RegionPose pose,
                        bool blockedStayBlocked, const Meets& meets) {
    if (!bounds.shaded) return false;
    const bool testLit = pose != RegionPose::Before;
    const bool testBlocked = pose != RegionPose::After && !blockedStayBlocked;
    for (std::size_t i = 0; i < lights.size() && i < 64; ++i) {
        const std::uint64_t bit = std::uint64_t{1} << i;
        if (testLit && (bounds.litLights & bit) && meets(bounds.litShadowOrigins, lights[i])) return true;
        if (testBlocked && (bounds.blockedLights & bit) && meets(bounds.blockedShadowOrigins, lights[i])) return true;
    }
    return false;
}

// Squared distance from `c` to { a + s * u : 0 <= s <= sMax } (a segment
// with sMax = 1, a ray with sMax = infinity); u in double.
double distanceToSpan2(const Vec3& c, const Vec3& a, const double (&u)[3], double sMax) {
    double ac[3], uu = 0.0, uac = 0.0;
    for (int k = 0; k < 3; ++k) {
        ac[k] = static_cast<double>(c[k]) - a[k];
        uu += u[k] * u[k];
        uac += u[k] * ac[k];
    }
    const double s = uu > 0.0 ? std::clamp(uac / uu, 0.0, sMax) : 0.0;
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double gap = ac[k] - s * u[k];
        sum += gap * gap;
    }
    return sum;
}

}  // namespace

bool RayTreeBounds::blockedRaysAllMeetBall(const Vec3& centre, float radius, float lightClearance,
                                           std::span<const Light> lights) const {
    if (blockedShadowOrigins.empty() || !(radius > 0.0f)) return false;
    if (lights.size() < 64 && (blockedLights >> lights.size()) != 0) return false;  // a light not given
    const double r2 = static_cast<double>(radius) * radius;
    const Box3& b = blockedShadowOrigins;
    for (std::size_t i = 0; i < lights.size() && i < 64; ++i) {
        if (!(blockedLights & (std::uint64_t{1} << i))) continue;
        const Light& light = lights[i];
        const bool directional = light.type == LightType::Directional;
        if (!directional && length(light.position - centre) <= lightClearance) return false;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 p{(corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y, (corner & 4) ? b.hi.z : b.lo.z};
            const Vec3 toward = directional ? -light.direction : light.position;
            double u[3];
            for (int k = 0; k < 3; ++k) u[k] = directional ? toward[k] : static_cast<double>(toward[k]) - p[k];
            const double d2 = distanceToSpan2(centre, p, u, directional ? kBoundsInfinity : 1.0);
            if (!(d2 <= r2)) return false;
        }
    }
    return true;
}

bool RayTreeBounds::mayMeetBall(const Vec3& centre, float radius, const Box3& box, std::span<const Light> lights,
                                RegionPose pose, bool blockedStayBlocked) const {
    if (dependsOnEverything) return true;
    if (box.empty()) return false;
    if (boxMeetsSegments(box, segmentStarts, segmentEnds) && ballMeetsSegments(centre, radius, segmentStarts, segmentEnds))
        return true;
    if (boxMeetsRays(box, escapeOrigins, escapeDirections) && ballMeetsRays(centre, radius, escapeOrigins, escapeDirections))
        return true;
    return shadowRayMayChange(*this, lights, pose, blockedStayBlocked, [&](const Box3& origins, const Light& light) {
        return light.type == LightType::Directional
                   ? boxMeetsSweep(box, origins, -light.direction) && ballMeetsSweep(centre, radius, origins, -light.direction)
                   : boxMeetsHull(box, origins, light.position) && ballMeetsHull(centre, radius, origins, light.position);
    });
}

bool RayTreeBounds::mayMeet(const Box3& box, std::span<const Light> lights, RegionPose pose,
                            bool blockedStayBlocked) const {
    if (dependsOnEverything) return true;
    if (box.empty()) return false;
    if (boxMeetsSegments(box, segmentStarts, segmentEnds)) return true;
    if (boxMeetsRays(box, escapeOrigins, escapeDirections)) return true;
    return shadowRayMayChange(*this, lights, pose, blockedStayBlocked, [&](const Box3& origins, const Light& light) {
        return light.type == LightType::Directional ? boxMeetsSweep(box, origins, -light.direction)
                                                    : boxMeetsHull(box, origins, light.position);
    });
}

}  // namespace raycache
