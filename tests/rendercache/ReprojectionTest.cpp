// reproject(): aging, eviction at the maximum age, the depth test, the second
// chance for losers, and its exact counts, on samples placed where a
// 90-degree camera at the origin sees them in closed form.
#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "rendercache/Reprojection.h"

using namespace raycache;

namespace {

constexpr int kSize = 10;
constexpr int kMargin = 1;

// At the origin looking down -z, 90 degrees, 10x10: the point at depth d
// whose continuous pixel position is (px, py) is (d (px - 5) / 5, d (5 - py) / 5, -d).
Camera eyeCamera() {
    return Camera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0f};
}
Vec3 at(float px, float py, float depth) {
    return {depth * (px - 5.0f) / 5.0f, depth * (5.0f - py) / 5.0f, -depth};
}

Scene twoObjects() {
    Scene scene;
    scene.objects.push_back(SceneObject{"a", Sphere{{0, 0, 0}, 1.0f}, Material{}, {0, 0, 0}});
    scene.objects.push_back(SceneObject{"b", Sphere{{2, 0, -5}, 1.0f}, Material{}, {2, 0, -5}});
    return scene;
}

struct Fixture {
    SamplePool pool;
    void put(std::size_t slot, int object, const Vec3& position, std::uint16_t age = 0) {
        pool.objectId[slot] = object;
        pool.position[slot] = position;
        pool.age[slot] = age;
    }
};

}  // namespace

TEST(Reprojection, AgesEvictsTestsDepthGivesLosersASecondChanceAndCountsExactly) {
    const Scene scene = twoObjects();
    const ScreenProjection projection(eyeCamera(), kSize, kSize);
    constexpr int kMaxAge = 3;
    for (int threads : {1, 2}) {
        Fixture f;
        f.pool.reset(24);
        f.put(0, 0, at(2.5f, 2.5f, 5));
        // Object b's origin moved from (1, 0, -5) to (2, 0, -5): its sample follows, one pixel to the right.
        f.put(1, 1, at(5.5f, 3.5f, 5) - Vec3{1, 0, -5});
        f.put(2, 0, at(1.5f, 7.5f, 5), kMaxAge - 1);  // one reprojection left
        f.put(3, 0, at(8.5f, 8.5f, 5), kMaxAge);      // too old
        f.put(4, 0, Vec3{0, 0, 5});                   // behind the eye
        f.put(5, 0, at(3.5f, 5.5f, 4));               // wins (3, 5)
        f.put(6, 0, at(3.8f, 5.6f, 6));               // loses (3, 5); nearest neighbour (4, 5) is empty
        f.put(7, 0, at(7.5f, 7.5f, 3));               // wins (7, 7)
        f.put(8, 0, at(7.7f, 7.6f, 5));               // loses (7, 7); (8, 7), (7, 8), (8, 8) taken: goes to (7, 6), the nearest empty of all 8
        f.put(9, 0, at(8.5f, 7.5f, 5));
        f.put(10, 0, at(7.5f, 8.5f, 5));
        f.put(11, 0, at(8.5f, 8.5f, 5));
        f.put(12, 0, at(1.5f, 1.5f, 2));                                   // wins (1, 1)
        f.put(13, 0, at(1.8f, 1.6f, 3));                                   // loses, takes (2, 1) ...
        f.put(14, 0, at(1.9f, 1.55f, 4));                                  // ... which it also wanted: farther, lost
        f.put(15, 0, at(-3.5f, 5.5f, 5));                                  // past the 1-pixel margin
        f.put(16, SamplePool::kBackground, normalize(at(0.3f, 9.5f, 1)));  // a miss, infinitely far
        f.put(17, 0, at(0.5f, 9.5f, 100));                                 // any surface beats it
        f.put(18, 0, at(10.5f, 4.5f, 5));                                  // in the margin: kept, not shown
        // Slots 19..23 stay empty.

        PointImage image;
        image.reset(kSize, kSize, kMargin);
        std::vector<unsigned char> shown;
        const Parallel parallel(threads);
        const ReprojectionCounts counts = reproject(f.pool, scene, projection, kMaxAge, image, shown, parallel);
        EXPECT_EQ(counts.placed, 15) << threads << " threads";
        EXPECT_EQ(counts.moved, 4);
        EXPECT_EQ(counts.lost, 3);
        EXPECT_EQ(counts.evicted, 1);

        const std::map<std::pair<int, int>, std::uint32_t> expected = {
            {{2, 2}, 0},  {{6, 3}, 1},  {{1, 7}, 2},  {{3, 5}, 5},  {{4, 5}, 6},   {{7, 7}, 7},  {{8, 7}, 9},
            {{7, 8}, 10}, {{8, 8}, 11}, {{1, 1}, 12}, {{2, 1}, 13}, {{-1, 9}, 16}, {{0, 9}, 17}, {{10, 4}, 18},
            {{7, 6}, 8},
        };
        for (int y = -kMargin; y < kSize + kMargin; ++y)
            for (int x = -kMargin; x < kSize + kMargin; ++x) {
                const auto e = expected.find({x, y});
                if (e == expected.end()) {
                    EXPECT_FALSE(image.hasSample(x, y)) << x << "," << y << " holds slot " << image.slotAt(x, y);
                } else {
                    ASSERT_TRUE(image.hasSample(x, y)) << x << "," << y;
                    EXPECT_EQ(image.slotAt(x, y), e->second) << x << "," << y;
                }
            }
        EXPECT_NEAR(image.depthAt(3, 5), 4.0f, 1e-5f);
        EXPECT_NEAR(image.depthAt(4, 5), 6.0f, 1e-5f) << "a moved sample keeps its own depth";
        EXPECT_EQ(image.depthAt(-1, 9), std::numeric_limits<float>::infinity());

        for (std::uint32_t slot : {3u, 4u, 14u, 15u}) EXPECT_TRUE(f.pool.empty(slot)) << slot << " freed";
        for (std::uint32_t slot : {0u, 1u, 2u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 12u, 13u, 16u, 17u, 18u}) {
            EXPECT_FALSE(f.pool.empty(slot)) << slot;
            EXPECT_NE(shown[slot], 0) << slot;
        }
        for (std::uint32_t slot : {3u, 4u, 14u, 15u, 19u}) EXPECT_EQ(shown[slot], 0) << slot;
        EXPECT_EQ(shown.size(), f.pool.capacity());
        EXPECT_EQ(f.pool.age[0], 1);
        EXPECT_EQ(f.pool.age[2], kMaxAge);
        EXPECT_EQ(f.pool.age[16], 1);
        EXPECT_TRUE(f.pool.empty(19));
    }
}

TEST(Reprojection, ASampleIsShownForMaxAgeReprojectionsAndEvictedOnTheNext) {
    const Scene scene = twoObjects();
    const ScreenProjection projection(eyeCamera(), kSize, kSize);
    const Parallel parallel(1);
    for (int maxAge : {1, 2, 5}) {
        SamplePool pool;
        pool.reset(1);
        pool.objectId[0] = 0;
        pool.position[0] = at(4.5f, 4.5f, 3);
        pool.age[0] = 0;  // just traced
        PointImage image;
        std::vector<unsigned char> shown;
        for (int frame = 1; frame <= maxAge; ++frame) {
            image.reset(kSize, kSize, kMargin);
            const ReprojectionCounts c = reproject(pool, scene, projection, maxAge, image, shown, parallel);
            ASSERT_EQ(c.placed, 1) << "max age " << maxAge << ", reprojection " << frame;
            ASSERT_EQ(c.evicted, 0);
            ASSERT_EQ(pool.age[0], frame);
            ASSERT_EQ(image.slotAt(4, 4), 0u);
        }
        image.reset(kSize, kSize, kMargin);
        const ReprojectionCounts c = reproject(pool, scene, projection, maxAge, image, shown, parallel);
        EXPECT_EQ(c.evicted, 1) << "max age " << maxAge;
        EXPECT_EQ(c.placed, 0);
        EXPECT_EQ(c.lost, 0);
        EXPECT_TRUE(pool.empty(0));
        EXPECT_FALSE(image.hasSample(4, 4));
    }
}
