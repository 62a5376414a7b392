#pragma once
// Axis-aligned box in 3-D: empty until a point is added.
#include <limits>

#include "core/Vec3.h"

namespace raycache {

struct Box3 {
    Vec3 lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
            std::numeric_limits<float>::infinity()};
    Vec3 hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
            -std::numeric_limits<float>::infinity()};

    bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    // Comparisons rather than std::fmin/fmax, which are calls: boxes grow
    // once per ray in animated scenes. A NaN coordinate is ignored.
    void add(const Vec3& p) {
        lo = {p.x < lo.x ? p.x : lo.x, p.y < lo.y ? p.y : lo.y, p.z < lo.z ? p.z : lo.z};
        hi = {p.x > hi.x ? p.x : hi.x, p.y > hi.y ? p.y : hi.y, p.z > hi.z ? p.z : hi.z};
    }
    void add(const Box3& b) {
        lo = {b.lo.x < lo.x ? b.lo.x : lo.x, b.lo.y < lo.y ? b.lo.y : lo.y, b.lo.z < lo.z ? b.lo.z : lo.z};
        hi = {b.hi.x > hi.x ? b.hi.x : hi.x, b.hi.y > hi.y ? b.hi.y : hi.y, b.hi.z > hi.z ? b.hi.z : hi.z};
    }
    bool overlaps(const Box3& b) const {
        return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y && lo.z <= b.hi.z &&
               b.lo.z <= hi.z;
    }
    // The box moved by `offset` (an empty box stays empty).
    Box3 shifted(const Vec3& offset) const { return empty() ? *this : Box3{lo + offset, hi + offset}; }
    // The box grown by `margin` on every side.
    Box3 grown(float margin) const {
        const Vec3 m{margin, margin, margin};
        return {lo - m, hi + m};
    }
};

}  // namespace raycache
