#pragma once
// Unit quaternions for rotations that are interpolated (animation keys):
// slerp turns at a constant rate, which blending matrices does not.
#include "core/Transform.h"
#include "core/Vec3.h"

namespace raycache {

struct Quaternion {
    float w = 1.0f;
    Vec3 v{0.0f, 0.0f, 0.0f};

    // Rotation about `axis` (any length > 0) by `degrees`, right-handed.
    static Quaternion fromAxisAngle(const Vec3& axis, float degrees);
    friend Quaternion operator*(const Quaternion& a, const Quaternion& b);  // b first, then a
    friend bool operator==(const Quaternion&, const Quaternion&) = default;
    Transform toTransform() const;
};

// Spherical interpolation from a (s = 0) to b (s = 1) the shorter way round.
Quaternion slerp(const Quaternion& a, const Quaternion& b, float s);

}  // namespace raycache
