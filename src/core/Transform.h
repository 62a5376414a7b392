#pragma once
// Affine transform (3x3 linear part + translation) for placing objects.
#include <array>

#include "core/Vec3.h"

namespace raycache {

class Transform {
public:
    Transform() = default;  // identity

    static Transform translate(const Vec3& t);
    static Transform scale(const Vec3& s);
    // Rotation about a unit axis by an angle in degrees (right-handed).
    static Transform rotate(const Vec3& axis, float degrees);

    // Composition: (a * b) applies b first, then a.
    friend Transform operator*(const Transform& a, const Transform& b);

    Vec3 applyToPoint(const Vec3& p) const;
    Vec3 applyToVector(const Vec3& v) const;
    // Normals transform by the inverse transpose of the linear part.
    Vec3 applyToNormal(const Vec3& n) const;

    Vec3 translation() const { return {m_[0][3], m_[1][3], m_[2][3]}; }
    // The matrix as three rows of (linear part | translation), e.g. for a
    // tracer's instance transform.
    using Rows = std::array<std::array<float, 4>, 3>;
    const Rows& rows() const { return m_; }
    static Transform fromRows(const Rows& rows);
    friend bool operator==(const Transform&, const Transform&) = default;
    float determinant() const;

private:
    Rows m_{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
};

}  // namespace raycache
