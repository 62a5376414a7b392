// ScreenProjection against its oracle, CameraRays: every point on the ray
// through a pixel centre lands in that pixel, at depth t * dot(dir, forward);
// and a few points whose image a pinhole camera gives in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "render/CameraRays.h"
#include "rendercache/ScreenProjection.h"

using namespace raycache;

namespace {

struct Case {
    Camera camera;
    int width, height;
};

}  // namespace

TEST(ScreenProjection, InvertsCameraRaysForEveryPixelAndDistance) {
    const Case cases[] = {
        {Camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.0f}, 64, 48},
        {Camera{{1, 2, 3}, {-2, 0.5f, -4}, {0, 1, 0}, 37.5f}, 33, 71},    // tall, odd fov
        {Camera{{-3, 4, 2}, {0, 1, 0}, {0.3f, 1, 0.2f}, 70.0f}, 80, 21},  // tilted up vector
        {Camera{{0, 10, 0}, {0, 0, 0}, {0, 0, -1}, 20.0f}, 17, 17},       // looking straight down
        {Camera{{5, 1, -5}, {4, 1, -5}, {0, -1, 0}, 100.0f}, 50, 30},     // upside down, wide
    };
    const float distances[] = {0.05f, 1.0f, 7.25f, 300.0f};
    for (const Case& c : cases) {
        const CameraRays rays(c.camera, c.width, c.height);
        const ScreenProjection projection(c.camera, c.width, c.height);
        const Vec3 forward = normalize(c.camera.lookAt - c.camera.position);
        for (int y = 0; y < c.height; ++y)
            for (int x = 0; x < c.width; ++x)
                for (float t : distances) {
                    const Ray ray = rays.ray(x, y);
                    const ScreenProjection::Projected p = projection.point(ray.origin + ray.direction * t);
                    ASSERT_EQ(static_cast<int>(std::floor(p.x)), x) << c.width << "x" << c.height << " t " << t;
                    ASSERT_EQ(static_cast<int>(std::floor(p.y)), y) << c.width << "x" << c.height << " t " << t;
                    // The pixel centre, up to float rounding of the ray and the point.
                    ASSERT_NEAR(p.x, static_cast<float>(x) + 0.5f, 2e-3f);
                    ASSERT_NEAR(p.y, static_cast<float>(y) + 0.5f, 2e-3f);
                    const float expectedDepth = t * dot(ray.direction, forward);
                    ASSERT_NEAR(p.depth, expectedDepth, 1e-5f * t + 1e-6f);
                    // A miss is stored as its direction: it lands on the same pixel.
                    const ScreenProjection::Projected d = projection.direction(ray.direction);
                    ASSERT_EQ(static_cast<int>(std::floor(d.x)), x);
                    ASSERT_EQ(static_cast<int>(std::floor(d.y)), y);
                }
    }
}

TEST(ScreenProjection, ClosedFormPointsOfANinetyDegreeCamera) {
    // At the origin looking down -z, 90 degrees: the image plane at distance d
    // spans [-d, d] both ways, so x = 50 (1 + X/d), y = 50 (1 - Y/d), depth -Z.
    const ScreenProjection p(Camera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0f}, 100, 100);
    const struct {
        Vec3 point;
        float x, y, depth;
    } expected[] = {
        {{0, 0, -5}, 50, 50, 5},    {{5, 0, -5}, 100, 50, 5},  {{-5, 0, -5}, 0, 50, 5},
        {{0, 5, -5}, 50, 0, 5},     {{0, -5, -5}, 50, 100, 5}, {{-5, -5, -5}, 0, 100, 5},
        {{1, 2, -4}, 62.5f, 25, 4}, {{3, -1, -2}, 125, 75, 2},  // off the image: still projected
    };
    for (const auto& e : expected) {
        const ScreenProjection::Projected q = p.point(e.point);
        EXPECT_NEAR(q.x, e.x, 1e-4f) << e.point.x << "," << e.point.y << "," << e.point.z;
        EXPECT_NEAR(q.y, e.y, 1e-4f) << e.point.x << "," << e.point.y << "," << e.point.z;
        EXPECT_FLOAT_EQ(q.depth, e.depth);
    }
    EXPECT_LT(p.point({0, 0, 3}).depth, 0.0f) << "behind the eye";
    // Non-square: the vertical fov holds, the horizontal extent follows the aspect.
    const ScreenProjection wide(Camera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0f}, 200, 100);
    EXPECT_NEAR(wide.point({5, 5, -5}).x, 150.0f, 1e-4f);  // X/d = 1 is half the half-width
    EXPECT_NEAR(wide.point({5, 5, -5}).y, 0.0f, 1e-4f);
    EXPECT_NEAR(wide.point({10, 0, -5}).x, 200.0f, 1e-4f);
}
