// RowRays: each pixel's ray is CameraRays::ray() bit for bit, asked for in
// any order, in the full blocks of sixteen and in a row's shorter last one.
#include <gtest/gtest.h>

#include <bit>

#include "rendercache/RowRays.h"

using namespace raycache;

TEST(RowRays, EachPixelsRayIsCameraRaysRayBitForBit) {
    constexpr int kWidth = 37, kHeight = 5;  // blocks of 16, 16 and 5
    const CameraRays rays(Camera{{1, 2, 3}, {-2, 0.5f, -4}, {0, 1, 0}, 50.0f}, kWidth, kHeight);
    const auto same = [](float a, float b) {
        return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
    };
    for (int y = 0; y < kHeight; ++y) {
        RowRays row(rays, y);
        for (const int x : {36, 0, 15, 16, 3, 35, 31, 32, 17, 20, 33, 1}) {
            const Ray expected = rays.ray(x, y);
            const Ray& got = row.at(x);
            EXPECT_TRUE(same(got.origin.x, expected.origin.x) && same(got.origin.y, expected.origin.y) &&
                        same(got.origin.z, expected.origin.z))
                << x << "," << y;
            EXPECT_TRUE(same(got.direction.x, expected.direction.x) && same(got.direction.y, expected.direction.y) &&
                        same(got.direction.z, expected.direction.z))
                << x << "," << y;
        }
    }
}
