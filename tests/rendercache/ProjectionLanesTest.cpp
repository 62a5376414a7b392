// projectSamples16() against the one-sample functions it stands for,
// projectPoint() and imagePixelOf(): the same landing, position, depth and
// pixels bit for bit, for blocks of every length up to sixteen, with
// misses, empty slots, points behind the eye and points that land off the
// image or past the range of int.
#include <gtest/gtest.h>

#include <bit>
#include <vector>

#include "rendercache/ProjectionLanes.h"
#include "rendercache/Reprojection.h"

using namespace raycache;

TEST(ProjectionLanes, EachLaneIsProjectPointAndImagePixelOfBitForBit) {
    constexpr int kWidth = 37, kHeight = 23;
    const ScreenProjection projection(Camera{{1, 2, 3}, {-2, 0.5f, -4}, {0, 1, 0}, 50.0f}, kWidth, kHeight);
    const ScreenProjection next(Camera{{1.2f, 2, 2.9f}, {-2, 0.4f, -4}, {0, 1, 0}, 50.0f}, kWidth, kHeight);
    const std::vector<Vec3> origins = {{0, 0, 0}, {-1.5f, 0.25f, -3}, {4, -1, 2}};
    std::uint64_t state = 99;
    const auto random = [&state](float lo, float hi) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return lo + (hi - lo) * static_cast<float>(state >> 40) / static_cast<float>(1ull << 24);
    };
    int landed = 0, offImage = 0;
    for (int block = 0; block < 400; ++block) {
        SamplePoint points[kFloatLanes];
        for (SamplePoint& p : points) {
            const float kind = random(0, 1);
            p.objectId = kind < 0.1f ? SamplePool::kEmpty : kind < 0.2f ? SamplePool::kBackground
                                                                        : static_cast<int>(random(0, 2.99f));
            // Mostly in front of the camera, some behind it or far to a side,
            // a few on the eye's plane (depth 0) or almost.
            p.position = p.objectId == SamplePool::kBackground ? Vec3{random(-1, 1), random(-1, 1), random(-1, 1)}
                                                                : Vec3{random(-9, 9), random(-6, 8), random(-14, 6)};
            if (kind > 0.97f) p.position = Vec3{1e-30f, 3e9f, -1e-30f};
        }
        for (const bool predicting : {true, false}) {
            const int count = 1 + block % kFloatLanes;
            ProjectedSamples out;
            projectSamples16(points, count, origins.data(), projection, predicting ? &next : nullptr, kWidth, kHeight,
                             out);
            for (int i = 0; i < count; ++i) {
                float px = 0, py = 0, depth = 0;
                const bool lands = points[i].objectId != SamplePool::kEmpty &&
                                   projectPoint(points[i], origins.data(), projection, px, py, depth);
                ASSERT_EQ(out.landed[i] != 0, lands) << "block " << block << ", lane " << i;
                if (predicting) {
                    const std::int32_t expected = points[i].objectId == SamplePool::kEmpty
                                                      ? -1
                                                      : imagePixelOf(points[i], origins.data(), next, kWidth, kHeight);
                    ASSERT_EQ(out.nextPixel[i], expected) << "block " << block << ", lane " << i;
                }
                if (!lands) continue;
                ++landed;
                EXPECT_EQ(std::bit_cast<std::uint32_t>(out.x[i]), std::bit_cast<std::uint32_t>(px));
                EXPECT_EQ(std::bit_cast<std::uint32_t>(out.y[i]), std::bit_cast<std::uint32_t>(py));
                EXPECT_EQ(std::bit_cast<std::uint32_t>(out.depth[i]), std::bit_cast<std::uint32_t>(depth));
                EXPECT_EQ(out.pixelX[i], ScreenProjection::pixelOf(px));
                EXPECT_EQ(out.pixelY[i], ScreenProjection::pixelOf(py));
                const int x = out.pixelX[i], y = out.pixelY[i];
                offImage += x < 0 || y < 0 || x >= kWidth || y >= kHeight ? 1 : 0;
            }
            for (int i = count; i < kFloatLanes; ++i) EXPECT_EQ(out.landed[i], 0) << "past the block's end";
        }
    }
    // Both ways of every test taken often enough to be tested.
    EXPECT_GT(landed, 1000);
    EXPECT_GT(offImage, 100);
}
