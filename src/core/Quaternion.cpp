#include "core/Quaternion.h"

#include <cmath>
#include <numbers>

namespace raycache {

Quaternion Quaternion::fromAxisAngle(const Vec3& axis, float degrees) {
    const float half = 0.5f * degrees * std::numbers::pi_v<float> / 180.0f;
    return {std::cos(half), normalize(axis) * std::sin(half)};
}

Quaternion operator*(const Quaternion& a, const Quaternion& b) {
    return {a.w * b.w - dot(a.v, b.v), b.v * a.w + a.v * b.w + cross(a.v, b.v)};
}

Transform Quaternion::toTransform() const {
    const float x = v.x, y = v.y, z = v.z;
    return Transform::fromRows({{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y), 0},
                                 {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x), 0},
                                 {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y), 0}}});
}

Quaternion slerp(const Quaternion& a, const Quaternion& bIn, float s) {
    Quaternion b = bIn;
    float c = a.w * b.w + dot(a.v, b.v);
    if (c < 0.0f) {  // q and -q are the same rotation: take the nearer one
        b = {-b.w, -b.v};
        c = -c;
    }
    float ka, kb;
    if (c > 0.9995f) {  // nearly equal: linear blend, renormalized below
        ka = 1.0f - s;
        kb = s;
    } else {
        const float angle = std::acos(c);
        const float sinAngle = std::sin(angle);
        ka = std::sin((1.0f - s) * angle) / sinAngle;
        kb = std::sin(s * angle) / sinAngle;
    }
    Quaternion q{a.w * ka + b.w * kb, a.v * ka + b.v * kb};
    const float norm = std::sqrt(q.w * q.w + dot(q.v, q.v));
    return {q.w / norm, q.v * (1.0f / norm)};
}

}  // namespace raycache
