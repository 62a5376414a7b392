#include "core/Optics.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace raycache;

namespace {
void expectNear(const Vec3& a, const Vec3& b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
}  // namespace

TEST(Optics, ReflectMirrorsAboutTheNormal) {
    const Vec3 i = normalize(Vec3{1, -1, 0});
    expectNear(reflect(i, {0, 1, 0}), normalize(Vec3{1, 1, 0}));
    // Head-on reflection reverses the ray.
    expectNear(reflect({0, 0, -1}, {0, 0, 1}), {0, 0, 1});
}

TEST(Optics, ReflectKeepsUnitLengthAndAngle) {
    const Vec3 n = normalize(Vec3{0.3f, 1, -0.2f});
    const Vec3 i = normalize(Vec3{0.7f, -0.4f, 0.1f});
    const Vec3 r = reflect(i, n);
    EXPECT_NEAR(length(r), 1.0f, 1e-6f);
    EXPECT_NEAR(dot(r, n), -dot(i, n), 1e-6f);
}

TEST(Optics, RefractObeysSnellIntoDenserMedium) {
    // 45 degrees from air (1.0) into glass (1.5): sin(theta_t) = sin(45)/1.5.
    const Vec3 i = normalize(Vec3{1, -1, 0});
    const auto t = refract(i, {0, 1, 0}, 1.0f / 1.5f);
    ASSERT_TRUE(t.has_value());
    const float sinT = std::sin(std::numbers::pi_v<float> / 4.0f) / 1.5f;
    expectNear(*t, {sinT, -std::sqrt(1.0f - sinT * sinT), 0.0f});
    EXPECT_NEAR(length(*t), 1.0f, 1e-6f);
}

TEST(Optics, RefractLeavingDenserMediumBendsAway) {
    // From glass into air at 30 degrees: sin(theta_t) = 1.5 sin(30) = 0.75.
    const float s = 0.5f, c = std::sqrt(0.75f);
    const auto t = refract({s, -c, 0}, {0, 1, 0}, 1.5f);
    ASSERT_TRUE(t.has_value());
    expectNear(*t, {0.75f, -std::sqrt(1.0f - 0.75f * 0.75f), 0.0f});
}

TEST(Optics, TotalInternalReflectionPastTheCriticalAngle) {
    // Critical angle for 1.5 -> 1.0 is asin(1/1.5) = 41.8 degrees.
    const auto angled = [](float degrees) {
        const float a = degrees * std::numbers::pi_v<float> / 180.0f;
        return Vec3{std::sin(a), -std::cos(a), 0};
    };
    EXPECT_TRUE(refract(angled(41.0f), {0, 1, 0}, 1.5f).has_value());
    EXPECT_FALSE(refract(angled(42.5f), {0, 1, 0}, 1.5f).has_value());
    // Never from the rarer side.
    EXPECT_TRUE(refract(angled(89.0f), {0, 1, 0}, 1.0f / 1.5f).has_value());
}

TEST(Optics, RefractWithEqualIndicesGoesStraight) {
    const Vec3 i = normalize(Vec3{0.2f, -0.9f, 0.3f});
    const auto t = refract(i, {0, 1, 0}, 1.0f);
    ASSERT_TRUE(t.has_value());
    expectNear(*t, i);
}
