#include "core/Transform.h"

#include <cmath>
#include <numbers>

namespace raycache {

Transform Transform::fromRows(const Rows& rows) {
    Transform r;
    r.m_ = rows;
    return r;
}

Transform Transform::translate(const Vec3& t) {
    Transform r;
    r.m_[0][3] = t.x;
    r.m_[1][3] = t.y;
    r.m_[2][3] = t.z;
    return r;
}

Transform Transform::scale(const Vec3& s) {
    Transform r;
    r.m_[0][0] = s.x;
    r.m_[1][1] = s.y;
    r.m_[2][2] = s.z;
    return r;
}

Transform Transform::rotate(const Vec3& axisIn, float degrees) {
    const Vec3 a = normalize(axisIn);
    const float rad = degrees * std::numbers::pi_v<float> / 180.0f;
    const float c = std::cos(rad), s = std::sin(rad), t = 1.0f - c;
    Transform r;
    r.m_[0] = {t * a.x * a.x + c, t * a.x * a.y - s * a.z, t * a.x * a.z + s * a.y, 0};
    r.m_[1] = {t * a.x * a.y + s * a.z, t * a.y * a.y + c, t * a.y * a.z - s * a.x, 0};
    r.m_[2] = {t * a.x * a.z - s * a.y, t * a.y * a.z + s * a.x, t * a.z * a.z + c, 0};
    return r;
}

Transform operator*(const Transform& a, const Transform& b) {
    Transform r;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 4; ++j) {
            float v = j == 3 ? a.m_[i][3] : 0.0f;
            for (int k = 0; k < 3; ++k) v += a.m_[i][k] * b.m_[k][j];
            r.m_[i][j] = v;
        }
    }
    return r;
}

Vec3 Transform::applyToVector(const Vec3& v) const {
    return {m_[0][0] * v.x + m_[0][1] * v.y + m_[0][2] * v.z,
            m_[1][0] * v.x + m_[1][1] * v.y + m_[1][2] * v.z,
            m_[2][0] * v.x + m_[2][1] * v.y + m_[2][2] * v.z};
}

Vec3 Transform::applyToPoint(const Vec3& p) const { return applyToVector(p) + translation(); }

Vec3 Transform::applyToNormal(const Vec3& n) const {
    // Cofactor matrix = det * inverse transpose; the scale is dropped by the
    // caller's normalization and the sign keeps orientation for mirrored transforms.
    const auto& m = m_;
    const Vec3 c0 = cross(Vec3{m[0][1], m[1][1], m[2][1]}, Vec3{m[0][2], m[1][2], m[2][2]});
    const Vec3 c1 = cross(Vec3{m[0][2], m[1][2], m[2][2]}, Vec3{m[0][0], m[1][0], m[2][0]});
    const Vec3 c2 = cross(Vec3{m[0][0], m[1][0], m[2][0]}, Vec3{m[0][1], m[1][1], m[2][1]});
    return c0 * n.x + c1 * n.y + c2 * n.z;
}

float Transform::determinant() const {
    const Vec3 c0{m_[0][0], m_[1][0], m_[2][0]};
    const Vec3 c1{m_[0][1], m_[1][1], m_[2][1]};
    const Vec3 c2{m_[0][2], m_[1][2], m_[2][2]};
    return dot(c0, cross(c1, c2));
}

}  // namespace raycache
