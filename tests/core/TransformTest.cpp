#include "core/Transform.h"

#include <gtest/gtest.h>

using namespace raycache;

namespace {
void expectVec3Near(const Vec3& a, const Vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
}  // namespace

TEST(Vec3, DotCrossLength) {
    EXPECT_FLOAT_EQ(dot(Vec3{1, 2, 3}, Vec3{4, -5, 6}), 12.0f);
    EXPECT_EQ(cross(Vec3{1, 0, 0}, Vec3{0, 1, 0}), (Vec3{0, 0, 1}));
    EXPECT_FLOAT_EQ(length(Vec3{3, 4, 12}), 13.0f);
    EXPECT_NEAR(length(normalize(Vec3{-2, 7, 1})), 1.0f, 1e-6f);
}

TEST(Transform, TranslateRotateScaleCompose) {
    const Transform t = Transform::translate({1, 2, 3}) * Transform::rotate({0, 0, 1}, 90.0f) *
                        Transform::scale({2, 2, 2});
    // Scale first, then rotate x onto y, then translate.
    expectVec3Near(t.applyToPoint({1, 0, 0}), {1, 4, 3});
    expectVec3Near(t.applyToVector({1, 0, 0}), {0, 2, 0});
    EXPECT_NEAR(t.determinant(), 8.0f, 1e-5f);
    expectVec3Near(t.translation(), {1, 2, 3});
}

TEST(Transform, NormalsUseInverseTranspose) {
    // Squash y: a 45-degree plane's normal must tilt toward y, not follow the points.
    const Transform t = Transform::scale({1, 0.5f, 1});
    const Vec3 n = normalize(t.applyToNormal(normalize(Vec3{1, 1, 0})));
    const Vec3 tangent = t.applyToVector(normalize(Vec3{1, -1, 0}));
    EXPECT_NEAR(dot(n, tangent), 0.0f, 1e-6f);
}

TEST(Transform, MirrorHasNegativeDeterminant) {
    EXPECT_LT(Transform::scale({-1, 1, 1}).determinant(), 0.0f);
}
