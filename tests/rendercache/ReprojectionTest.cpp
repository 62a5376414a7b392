// reproject(): aging, eviction at the maximum age, the depth test, the second
// chance for losers, the winners moved to their pixels' slots of the other
// pool, and its exact counts, on samples placed where a 90-degree camera at
// the origin sees them in closed form.
#include <gtest/gtest.h>

#include <algorithm>
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

// The image's pixel slots (12 x 12 with the margin) and room for predicted samples after them.
constexpr std::size_t kPixelSlots = (kSize + 2 * kMargin) * (kSize + 2 * kMargin);
constexpr std::size_t kOverflow = 24;

// The records of the slots a reader may look at (SamplePool::used()):
// the overflow slots never taken hold memory nobody wrote.
template <typename Records>
std::vector<typename Records::value_type> usedOf(const Records& records, const SamplePool& pool) {
    return {records.begin(), records.begin() + static_cast<std::ptrdiff_t>(pool.used())};
}

struct Fixture {
    SamplePool pool;
    Fixture() { pool.reset(kPixelSlots, kOverflow); }
    // Sample `i` in overflow slot i, where predicted samples wait for a pixel.
    void put(std::size_t i, int object, const Vec3& position, std::uint16_t age = 0) {
        const std::size_t slot = kPixelSlots + i;
        while (pool.overflowUsed <= i) pool.takeOverflowSlot();
        pool.point[slot].objectId = object;
        pool.point[slot].position = position;
        pool.look[slot].age = age;
    }
};

}  // namespace

TEST(Reprojection, AgesEvictsTestsDepthGivesLosersASecondChanceAndCountsExactly) {
    const Scene scene = twoObjects();
    const ScreenProjection projection(eyeCamera(), kSize, kSize);
    constexpr int kMaxAge = 3;
    for (int threads : {1, 2}) {
        Fixture f;
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
        // Overflow slots 19..23 stay empty, and so do the pixel slots.

        PointImage image;
        image.reset(kSize, kSize, kMargin);
        ASSERT_EQ(image.pixelCount(), kPixelSlots);
        SamplePool to;
        to.reset(kPixelSlots, kOverflow);
        // Left over from an earlier frame: every pixel slot is written.
        for (std::size_t slot = 0; slot < kPixelSlots; ++slot) to.point[slot].objectId = 0;
        to.overflowUsed = 3;
        const SamplePool before = f.pool;
        ReprojectionScratch scratch;
        const Parallel parallel(threads);
        const ReprojectionCounts counts = reproject(f.pool, to, scene, projection, kMaxAge, image, parallel, scratch);
        EXPECT_EQ(counts.placed, 15) << threads << " threads";
        EXPECT_EQ(counts.moved, 4);
        EXPECT_EQ(counts.lost, 3);
        EXPECT_EQ(counts.evicted, 1);
        // What the passes touched: 19 samples, of which all but the evicted
        // one, the one behind the eye and the one past the margin are
        // offered a pixel; 6, 8, 13, 14 and 16 (pushed out by 17) lose the
        // first round.
        EXPECT_EQ(counts.live, 19);
        EXPECT_EQ(counts.offered, 16);
        EXPECT_EQ(counts.secondChances, 5);
        EXPECT_EQ(counts.farOffers, 0);
        EXPECT_EQ(counts.reshadeCopied, 0);
        EXPECT_EQ(counts.texturingCopied, 0);

        // Pixel -> the sample that wins it.
        const std::map<std::pair<int, int>, std::size_t> expected = {
            {{2, 2}, 0},  {{6, 3}, 1},  {{1, 7}, 2},  {{3, 5}, 5},  {{4, 5}, 6},   {{7, 7}, 7},  {{8, 7}, 9},
            {{7, 8}, 10}, {{8, 8}, 11}, {{1, 1}, 12}, {{2, 1}, 13}, {{-1, 9}, 16}, {{0, 9}, 17}, {{10, 4}, 18},
            {{7, 6}, 8},
        };
        for (int y = -kMargin; y < kSize + kMargin; ++y)
            for (int x = -kMargin; x < kSize + kMargin; ++x) {
                const std::size_t pixel = image.pixelIndex(x, y);
                const auto e = expected.find({x, y});
                if (e == expected.end()) {
                    EXPECT_FALSE(image.hasSample(x, y)) << x << "," << y << " holds a sample";
                    EXPECT_TRUE(to.empty(pixel)) << x << "," << y;
                    continue;
                }
                ASSERT_TRUE(image.hasSample(x, y)) << x << "," << y;
                const std::size_t source = kPixelSlots + e->second;
                EXPECT_EQ(to.point[pixel].objectId, before.point[source].objectId) << x << "," << y;
                EXPECT_EQ(to.point[pixel].position, before.point[source].position) << x << "," << y;
                EXPECT_EQ(to.look[pixel].age, before.look[source].age + 1) << x << "," << y << ": aged by one frame";
            }
        EXPECT_NEAR(image.depthAt(3, 5), 4.0f, 1e-5f);
        EXPECT_NEAR(image.depthAt(4, 5), 6.0f, 1e-5f) << "a moved sample keeps its own depth";
        EXPECT_EQ(image.depthAt(-1, 9), std::numeric_limits<float>::infinity());
        EXPECT_EQ(to.look[image.pixelIndex(1, 7)].age, kMaxAge);
        EXPECT_EQ(to.overflowUsed, 0u) << "no sample is left without a pixel";
        EXPECT_EQ(to.used(), kPixelSlots);
        // The source is only read.
        EXPECT_EQ(usedOf(f.pool.point, f.pool), usedOf(before.point, before));
        EXPECT_EQ(usedOf(f.pool.look, f.pool), usedOf(before.look, before));
        EXPECT_EQ(f.pool.overflowUsed, before.overflowUsed);
    }
}

TEST(Reprojection, ASampleIsShownForMaxAgeReprojectionsAndEvictedOnTheNext) {
    const Scene scene = twoObjects();
    const ScreenProjection projection(eyeCamera(), kSize, kSize);
    const Parallel parallel(1);
    for (int maxAge : {1, 2, 5}) {
        Fixture f;
        f.put(0, 0, at(4.5f, 4.5f, 3));  // just traced
        SamplePool& pool = f.pool;
        SamplePool spare;
        spare.reset(kPixelSlots, kOverflow);
        PointImage image;
        ReprojectionScratch scratch;
        for (int frame = 1; frame <= maxAge; ++frame) {
            image.reset(kSize, kSize, kMargin);
            const ReprojectionCounts c = reproject(pool, spare, scene, projection, maxAge, image, parallel, scratch);
            std::swap(pool, spare);
            ASSERT_EQ(c.placed, 1) << "max age " << maxAge << ", reprojection " << frame;
            ASSERT_EQ(c.evicted, 0);
            ASSERT_TRUE(image.hasSample(4, 4));
            ASSERT_EQ(pool.look[image.pixelIndex(4, 4)].age, frame);
        }
        image.reset(kSize, kSize, kMargin);
        const ReprojectionCounts c = reproject(pool, spare, scene, projection, maxAge, image, parallel, scratch);
        std::swap(pool, spare);
        EXPECT_EQ(c.evicted, 1) << "max age " << maxAge;
        EXPECT_EQ(c.placed, 0);
        EXPECT_EQ(c.lost, 0);
        EXPECT_TRUE(pool.empty(image.pixelIndex(4, 4)));
        EXPECT_FALSE(image.hasSample(4, 4));
    }
}

// Many samples, many collisions, pixel slots and overflow slots alike (the
// way a frame leaves them: reprojected, fresh and predicted samples): every
// sample that wins a pixel lands in that pixel's slot with all its fields,
// the reshading ones included where they mean something, and one or two
// threads give the same pool.
TEST(Reprojection, EveryWinnerMovesToItsPixelsSlotWithAllItsFieldsOnAnyThreadCount) {
    const Scene scene = twoObjects();
    const ScreenProjection projection(eyeCamera(), kSize, kSize);
    SamplePool from;
    from.reset(kPixelSlots, kOverflow);
    while (from.overflowUsed < 20) from.takeOverflowSlot();
    for (std::size_t slot = 0; slot < from.used(); ++slot) {
        const std::uint32_t h = static_cast<std::uint32_t>(slot) * 2654435761u;
        if (h % 5 == 0) continue;  // some slots empty
        from.point[slot].objectId = 0;
        from.point[slot].position = at(-1.0f + static_cast<float>(h % 1200) / 100.0f,
                                 -1.0f + static_cast<float>((h >> 11) % 1200) / 100.0f,
                                 1.0f + static_cast<float>((h >> 22) % 5));  // few depths: ties
        from.look[slot].color = Rgb{static_cast<float>(slot), 1.0f, 2.0f};
        from.look[slot].age = static_cast<std::uint16_t>(h % 3);
        from.look[slot].viewDependent = slot % 2;
        from.look[slot].textured = slot % 3 == 0 ? 1 : 0;
        from.reshade[slot].primitiveId = static_cast<int>(slot) + 7;
        from.reshade[slot].baryU = 0.25f;
        from.reshade[slot].baryV = static_cast<float>(slot);
        from.reshade[slot].viewIndependent = Rgb{0.5f, static_cast<float>(slot), 0.0f};
        from.reshade[slot].litMask = slot * 3;
    }
    SamplePool reference;
    for (int threads : {1, 2}) {
        SamplePool to;
        to.reset(kPixelSlots, kOverflow);
        PointImage image;
        image.reset(kSize, kSize, kMargin);
        ReprojectionScratch scratch;
        const ReprojectionCounts c = reproject(from, to, scene, projection, 32, image, Parallel(threads), scratch);
        EXPECT_GT(c.lost, 0) << "the samples collide";
        EXPECT_GT(c.moved, 0);
        std::int64_t placed = 0, viewDependent = 0, textured = 0;
        for (int y = -kMargin; y < kSize + kMargin; ++y)
            for (int x = -kMargin; x < kSize + kMargin; ++x) {
                const std::size_t pixel = image.pixelIndex(x, y);
                ASSERT_EQ(image.hasSample(x, y), !to.empty(pixel));
                if (to.empty(pixel)) continue;
                ++placed;
                viewDependent += to.look[pixel].viewDependent;
                textured += to.look[pixel].textured;
                // The sample it came from: its colour names it.
                const auto source = static_cast<std::size_t>(to.look[pixel].color.r);
                ASSERT_EQ(to.point[pixel].position, from.point[source].position);
                ASSERT_EQ(to.look[pixel].age, from.look[source].age + 1);
                ASSERT_EQ(to.look[pixel].viewDependent, from.look[source].viewDependent);
                if (to.look[pixel].viewDependent) {
                    ASSERT_EQ(to.reshade[pixel].primitiveId, from.reshade[source].primitiveId);
                    ASSERT_EQ(to.reshade[pixel].baryV, from.reshade[source].baryV);
                    ASSERT_EQ(to.reshade[pixel].viewIndependent, from.reshade[source].viewIndependent);
                    ASSERT_EQ(to.reshade[pixel].litMask, from.reshade[source].litMask);
                }
            }
        EXPECT_EQ(placed, c.placed);
        EXPECT_EQ(viewDependent, c.reshadeCopied);
        EXPECT_EQ(textured, c.texturingCopied);
        EXPECT_GT(viewDependent, 0);
        EXPECT_GT(textured, 0);
        EXPECT_EQ(c.live, c.placed + c.lost + c.evicted);
        if (threads == 1) {
            reference = to;
            continue;
        }
        EXPECT_EQ(usedOf(to.point, to), usedOf(reference.point, reference));
        EXPECT_EQ(usedOf(to.look, to), usedOf(reference.look, reference));
    }
}

// With the next frame's camera given, reproject() tells for every pixel slot
// where its sample will land through it, as projecting the moved sample
// again would: the prediction needs no pass of its own over the pool.
TEST(Reprojection, ThroughThePredictedCameraEveryPixelSlotKnowsWhereItsSampleWillLand) {
    const Scene scene = twoObjects();
    const ScreenProjection projection(eyeCamera(), kSize, kSize);
    Camera nextCamera = eyeCamera();
    nextCamera.position = {0.6f, -0.3f, 0.0f};  // about one pixel left and half a pixel up at depth 5
    nextCamera.lookAt = nextCamera.position + Vec3{0, 0, -1};
    const ScreenProjection next(nextCamera, kSize, kSize);
    Fixture f;
    for (std::size_t i = 0; i < 12; ++i)
        f.put(i, 0, at(0.5f + static_cast<float>(i % 10), 0.5f + static_cast<float>(i) * 0.8f, 5));
    f.put(12, 0, at(9.7f, 9.5f, 5));  // lands in the image, off it through the next camera
    SamplePool to;
    to.reset(kPixelSlots, kOverflow);
    PointImage image;
    image.reset(kSize, kSize, kMargin);
    ReprojectionScratch scratch;
    std::vector<std::int32_t> nextPixel;
    const std::vector<Vec3> origins = objectOrigins(scene);
    for (int threads : {1, 2}) {
        image.reset(kSize, kSize, kMargin);
        reproject(f.pool, to, scene, projection, 32, image, Parallel(threads), scratch, &next, &nextPixel);
        ASSERT_EQ(nextPixel.size(), kPixelSlots);
        int landing = 0, off = 0;
        for (std::size_t slot = 0; slot < kPixelSlots; ++slot) {
            if (to.empty(slot)) {
                EXPECT_EQ(nextPixel[slot], -1) << slot;
                continue;
            }
            EXPECT_EQ(nextPixel[slot], imagePixelThrough(to, slot, origins, next, kSize, kSize)) << slot;
            (nextPixel[slot] >= 0 ? landing : off) += 1;
        }
        EXPECT_EQ(landing + off, 13);
        EXPECT_GT(off, 0);
    }
}

namespace {

// The rule of reproject() written plainly, one sample at a time, as the
// oracle for the banded, list-driven implementation: pixel -> (depth, slot)
// of its winner, and whether it won on the second chance.
struct OracleWinner {
    float depth;
    std::uint32_t slot;
    bool moved;
};
std::map<std::pair<int, int>, OracleWinner> oracle(const SamplePool& pool, const Scene& scene,
                                                   const ScreenProjection& projection, int maxAge,
                                                   const PointImage& shape) {
    const std::vector<Vec3> origins = objectOrigins(scene);
    struct Landing {
        std::uint32_t slot;
        float x, y, depth;
    };
    std::vector<Landing> landed;
    for (std::size_t slot = 0; slot < pool.used(); ++slot) {
        if (pool.empty(slot) || pool.look[slot].age >= maxAge) continue;
        float px, py, depth;
        if (!projectSample(pool, slot, origins, projection, px, py, depth)) continue;
        if (!shape.covers(static_cast<int>(std::floor(px)), static_cast<int>(std::floor(py)))) continue;
        landed.push_back({static_cast<std::uint32_t>(slot), px, py, depth});
    }
    const auto nearer = [](float d, std::uint32_t s, const OracleWinner& w) {
        return d < w.depth || (d == w.depth && s < w.slot);
    };
    std::map<std::pair<int, int>, OracleWinner> first;
    for (const Landing& l : landed) {
        const std::pair<int, int> p{static_cast<int>(std::floor(l.x)), static_cast<int>(std::floor(l.y))};
        const auto it = first.find(p);
        if (it == first.end() || nearer(l.depth, l.slot, it->second)) first[p] = {l.depth, l.slot, false};
    }
    std::map<std::pair<int, int>, OracleWinner> second;
    for (const Landing& l : landed) {
        const int x = static_cast<int>(std::floor(l.x)), y = static_cast<int>(std::floor(l.y));
        if (first.at({x, y}).slot == l.slot) continue;
        float best = 1e30f;
        std::pair<int, int> target{0, 0};
        bool found = false;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                if ((dx == 0 && dy == 0) || !shape.covers(x + dx, y + dy) || first.count({x + dx, y + dy})) continue;
                const float ex = static_cast<float>(dx) - (l.x - static_cast<float>(x) - 0.5f);
                const float ey = static_cast<float>(dy) - (l.y - static_cast<float>(y) - 0.5f);
                if (ex * ex + ey * ey < best) {
                    best = ex * ex + ey * ey;
                    target = {x + dx, y + dy};
                    found = true;
                }
            }
        if (!found) continue;
        const auto it = second.find(target);
        if (it == second.end() || nearer(l.depth, l.slot, it->second)) second[target] = {l.depth, l.slot, true};
    }
    first.insert(second.begin(), second.end());
    return first;
}

}  // namespace

// A tall image (several bands of rows tested in parallel) and samples that
// land far from the rows they sat in (moved more than half a band: tested
// on one thread afterwards), plus predicted samples in the overflow:
// whatever the path, the outcome is the plain rule's, on any thread count.
TEST(Reprojection, BandsFarSamplesAndOverflowGiveThePlainRulesOutcome) {
    constexpr int kW = 6, kH = 160, kM = 2;
    const Scene scene = twoObjects();
    // 90 degrees vertically; at depth d, pixel row py is at height d (80 - py) / 80.
    const Camera camera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0f};
    const ScreenProjection projection(camera, kW, kH);
    const auto point = [&](float px, float py, float depth) {
        return Vec3{depth * (px - 3.0f) / 80.0f, depth * (80.0f - py) / 80.0f, -depth};
    };
    PointImage image;
    image.reset(kW, kH, kM);
    const std::size_t pixelSlots = image.pixelCount();
    SamplePool from;
    from.reset(pixelSlots, 64);
    while (from.overflowUsed < 40) from.takeOverflowSlot();
    for (std::size_t slot = 0; slot < from.used(); ++slot) {
        const std::uint32_t h = static_cast<std::uint32_t>(slot) * 2654435761u ^ 0x9e3779b9u;
        if (h % 7 == 0) continue;
        // Most land near the row their slot belongs to; every fifth lands anywhere.
        const float row = slot < pixelSlots ? static_cast<float>(slot / (kW + 2 * kM)) - kM : 0.0f;
        const bool far = h % 5 == 0 || slot >= pixelSlots;
        const float py = far ? -1.5f + static_cast<float>((h >> 8) % 16300) / 100.0f
                             : row + static_cast<float>((h >> 8) % 700) / 100.0f - 3.0f;
        const float px = -1.5f + static_cast<float>((h >> 20) % 850) / 100.0f;
        from.point[slot].objectId = 0;
        from.point[slot].position = point(px, py, 1.0f + static_cast<float>((h >> 3) % 4));  // few depths: ties
        from.look[slot].age = static_cast<std::uint16_t>(h % 4);
    }
    const auto expected = oracle(from, scene, projection, 3, image);
    std::size_t moved = 0;
    for (const auto& [pixel, winner] : expected) moved += winner.moved ? 1 : 0;
    ASSERT_GT(moved, 10u) << "the second chance must be exercised";
    for (int threads : {1, 2, 3}) {
        image.reset(kW, kH, kM);
        SamplePool to;
        to.reset(pixelSlots, 64);
        ReprojectionScratch scratch;
        const ReprojectionCounts c = reproject(from, to, scene, projection, 3, image, Parallel(threads), scratch);
        EXPECT_EQ(c.placed, static_cast<std::int64_t>(expected.size())) << threads << " threads";
        EXPECT_EQ(c.moved, static_cast<std::int64_t>(moved));
        std::size_t far = 0;
        for (const auto& list : scratch.far) far += list.size();
        EXPECT_GT(far, 20u) << "samples landing far from their band must be exercised";
        EXPECT_EQ(c.farOffers, static_cast<std::int64_t>(far));
        std::size_t losers = 0;
        for (const auto& list : scratch.losers) losers += list.size();
        EXPECT_EQ(c.secondChances, static_cast<std::int64_t>(losers));
        // Offered: the live samples young enough that land in the image or its margin.
        std::int64_t landing = 0;
        for (std::size_t slot = 0; slot < from.used(); ++slot) {
            int x, y;
            float depth;
            if (from.empty(slot) || from.look[slot].age >= 3 ||
                !projectSample(from, slot, objectOrigins(scene), projection, x, y, depth))
                continue;
            landing += image.covers(x, y) ? 1 : 0;
        }
        EXPECT_EQ(c.offered, landing);
        EXPECT_GT(scratch.far.size(), 4u) << "several bands";
        for (int y = -kM; y < kH + kM; ++y)
            for (int x = -kM; x < kW + kM; ++x) {
                const auto e = expected.find({x, y});
                const std::size_t pixel = image.pixelIndex(x, y);
                if (e == expected.end()) {
                    ASSERT_TRUE(to.empty(pixel)) << x << "," << y << ", " << threads << " threads";
                    continue;
                }
                ASSERT_FALSE(to.empty(pixel)) << x << "," << y << ", " << threads << " threads";
                ASSERT_EQ(to.point[pixel].position, from.point[e->second.slot].position) << x << "," << y;
                ASSERT_EQ(image.depthAt(x, y), e->second.depth) << x << "," << y;
            }
    }
}
