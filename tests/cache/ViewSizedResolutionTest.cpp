// Resolution from the view (cache/ViewSizedResolution.h,
// RayCacheSettings::resolutionFromView): the policy that picks a cube's
// resolution from its lookups' footprints, resampling against the
// OpenGL-exact addressing of a cube of the new size, inherited colours that
// answer only footprints as wide as they are, and whole renders against the
// uncached render (the ground truth) and across thread counts.
#include <gtest/gtest.h>

#include "CdctFixtures.h"
#include "PathRender.h"

#include <random>
#include <set>
#include <vector>

#include "cache/CubeAddressing.h"
#include "cache/RayCache.h"
#include "cache/ViewSizedResolution.h"

using namespace raycache;

namespace {

using cdct_test::oneCctMirror;
using cdct_test::randomDirection;

ViewSizedResolution::LookupsByLevel lookupsAt(int level, std::uint64_t count) {
    ViewSizedResolution::LookupsByLevel lookups{};
    lookups[static_cast<std::size_t>(level)] = count;
    return lookups;
}

// A footprint (spread, radians) that allows exactly `level` below a full
// resolution of `fullSize` at error bound 1: level k's texels span 2^(k+1) / n.
float spreadAllowing(int level, int fullSize) {
    return static_cast<float>(2 << level) / static_cast<float>(fullSize) * 1.01f;
}

}  // namespace

TEST(ViewSizedResolution, ResolutionsHalveExactlyDownTo16) {
    EXPECT_EQ(ViewSizedResolution(512).coarsestLevel(), 5);  // 512 ... 16
    EXPECT_EQ(ViewSizedResolution(48).coarsestLevel(), 1);   // 48, 24
    EXPECT_EQ(ViewSizedResolution(300).coarsestLevel(), 2);  // 300, 150, 75: 37 would not cover 2×2 of 75
    EXPECT_EQ(ViewSizedResolution(8).coarsestLevel(), 0);    // lowered below 16 by the memory budget: stays
    EXPECT_EQ(ViewSizedResolution(512).size(), 512);
}

TEST(ViewSizedResolution, LevelAllowedFollowsTheTexelAngle) {
    const ViewSizedResolution r(512);
    EXPECT_EQ(r.levelAllowed(0.0f, 0.25f), 0);
    EXPECT_EQ(r.levelAllowed(spreadAllowing(2, 512), 1.0f), 2);
    EXPECT_EQ(r.levelAllowed(spreadAllowing(2, 512) * 0.98f, 1.0f), 1);
    EXPECT_EQ(r.levelAllowed(10.0f, 1.0f), 5);  // never past 16²
}

TEST(ViewSizedResolution, FirstFrameDecidesGrowingIsImmediateShrinkingWaits) {
    ViewSizedResolution r(512);
    EXPECT_EQ(r.afterFrame({}), 0);              // nothing looked it up: unchanged
    EXPECT_EQ(r.afterFrame(lookupsAt(3, 50)), 3);  // the first frame with lookups decides at once
    EXPECT_EQ(r.size(), 64);
    EXPECT_EQ(r.afterFrame(lookupsAt(1, 50)), 1);  // finer wanted: at once
    for (int frame = 1; frame < ViewSizedResolution::kFramesBeforeCoarser; ++frame)
        EXPECT_EQ(r.afterFrame(lookupsAt(frame % 2 ? 4 : 3, 50)), 1) << frame;
    // The fourth frame in a row wanting coarser: the finest those frames wanted.
    EXPECT_EQ(r.afterFrame(lookupsAt(4, 50)), 3);
    // A frame that wants the current level breaks the run.
    for (int frame = 1; frame < ViewSizedResolution::kFramesBeforeCoarser; ++frame) r.afterFrame(lookupsAt(5, 9));
    r.afterFrame(lookupsAt(3, 9));
    EXPECT_EQ(r.afterFrame(lookupsAt(5, 9)), 3);
}

TEST(ViewSizedResolution, OnePercentOfLookupsMayWantFiner) {
    ViewSizedResolution::LookupsByLevel lookups{};
    lookups[0] = 1;
    lookups[3] = 99;
    EXPECT_EQ(ViewSizedResolution(512).afterFrame(lookups), 3);
    lookups[0] = 2;
    lookups[3] = 98;
    EXPECT_EQ(ViewSizedResolution(512).afterFrame(lookups), 0);
}

TEST(CachingCubeResample, ACoarserTexelHoldsAStoreWhoseDirectionAddressesIt) {
    // The oracle is the addressing of a cube of the coarser size (itself
    // checked against OpenGL in CubeAddressingGlTest).
    CachingCube fine(Vec3{}, 64);
    std::mt19937 rng(5);
    std::vector<Vec3> stored;
    for (int i = 0; i < 3000; ++i) {
        const Vec3 d = randomDirection(rng);
        if (fine.writeIfInvalid(fine.texelIndexFor(d), static_cast<std::uint32_t>(i))) stored.push_back(d);
    }
    for (const int size : {32, 16}) {
        const CachingCube coarse = fine.resampled(size);
        std::set<int> addressed;
        for (const Vec3& d : stored) addressed.insert(coarse.texelIndexFor(d));
        EXPECT_EQ(coarse.validCount(), addressed.size()) << size;
        for (const int t : addressed) {
            ASSERT_TRUE(coarse.isValid(t));
            EXPECT_EQ(coarse.inheritedLevels(t), 0);  // a stored ray's own texel, only wider
            // The word is one of the stores addressed into this texel.
            bool fromThisTexel = false;
            for (std::size_t i = 0; i < stored.size() && !fromThisTexel; ++i)
                fromThisTexel = coarse.texelIndexFor(stored[i]) == t &&
                                fine.texels()[static_cast<std::size_t>(fine.texelIndexFor(stored[i]))] == coarse.texels()[static_cast<std::size_t>(t)];
            EXPECT_TRUE(fromThisTexel) << "texel " << t << " at " << size;
        }
    }
}

TEST(CachingCubeResample, FinerTexelsInheritAndTheirOwnStoreReplacesThem) {
    CachingCube coarse(Vec3{}, 16);
    const Vec3 d = normalize(Vec3{0.3f, 0.2f, 1.0f});
    ASSERT_TRUE(coarse.writeIfInvalid(coarse.texelIndexFor(d), 7u));
    std::vector<int> sourceOf;
    CachingCube fine = coarse.resampled(64, &sourceOf);
    EXPECT_EQ(fine.validCount(), 16u);  // the 4×4 texels under it
    const int t = fine.texelIndexFor(d);
    ASSERT_TRUE(fine.isValid(t));
    EXPECT_EQ(fine.inheritedLevels(t), 2);
    EXPECT_EQ(fine.texels()[static_cast<std::size_t>(t)], 7u);
    EXPECT_EQ(sourceOf[static_cast<std::size_t>(t)], coarse.texelIndexFor(d));
    EXPECT_TRUE(fine.writeIfInvalid(t, 9u));   // the texel's own colour replaces the inherited one
    EXPECT_FALSE(fine.writeIfInvalid(t, 11u));  // and is then written once, as any texel
    EXPECT_EQ(fine.inheritedLevels(t), 0);
    EXPECT_EQ(fine.texels()[static_cast<std::size_t>(t)], 9u);
    // Back to 32: the texel over t prefers t's own colour to its inherited siblings'.
    const CachingCube back = fine.resampled(32);
    const int u = back.texelIndexFor(d);
    EXPECT_EQ(back.texels()[static_cast<std::size_t>(u)], 9u);
    EXPECT_EQ(back.inheritedLevels(u), 0);
    // A texel with only inherited colours under it stays inherited, one level less.
    int inheritedOnly = 0;
    for (int i = 0; i < static_cast<int>(back.texelCount()); ++i)
        if (back.isValid(i) && i != u) {
            EXPECT_EQ(back.inheritedLevels(i), 1);
            ++inheritedOnly;
        }
    EXPECT_EQ(inheritedOnly, 3);
}

TEST(CachingCubeResample, OnlyPowerOfTwoStepsOfColourCubes) {
    EXPECT_THROW(CachingCube(Vec3{}, 48).resampled(16), std::logic_error);
    EXPECT_THROW(CachingCube(Vec3{}, 16, Vec3{1, 1, 1}).resampled(32), std::logic_error);
    EXPECT_NO_THROW(CachingCube(Vec3{}, 48).resampled(24));
}

TEST(ViewSizedCube, WideFootprintsShrinkTheCubeAndNarrowOnesGrowIt) {
    RayCacheSettings settings;
    settings.resolutionFromView = true;
    settings.levelErrorBound = 1.0f;
    RayCache cache(oneCctMirror(64), settings);
    auto workers = cache.makeWorkers(1);
    const auto lookUp = [&](const Vec3& d, float spread, Rgb& color, int& storeTexel) {
        const RayCache::Query q{0, d * 1.001f, d, spread};
        unsigned char found = 0;
        cache.lookupBatch(std::span(&q, 1), std::span(&color, 1), std::span(&found, 1), std::span(&storeTexel, 1),
                          workers[0]);
        return found != 0;
    };
    // Frame 1: wide footprints (level 2 of 64: 16² faces), one store each.
    std::mt19937 rng(9);
    std::vector<Vec3> directions;
    for (int i = 0; i < 200; ++i) directions.push_back(randomDirection(rng));
    cache.beginFrame(workers);
    workers[0].beginBatch(0);
    for (std::size_t i = 0; i < directions.size(); ++i) {
        Rgb color;
        int storeTexel = -1;
        ASSERT_FALSE(lookUp(directions[i], spreadAllowing(2, 64), color, storeTexel));
        cache.store(0, directions[i] * 1.001f, directions[i], Rgb{static_cast<float>(i), 0, 0}, 3.0f, workers[0],
                    storeTexel);
    }
    FrameCacheStats stats = cache.endFrame(workers);
    EXPECT_EQ(stats.objects[0].resolution, 64);
    EXPECT_EQ(stats.objects[0].resizedTo, 16);
    EXPECT_EQ(cache.cube(0).size(), 16);

    // Frame 2: the same wide footprints are answered from the 16² cube.
    cache.beginFrame(workers);
    workers[0].beginBatch(0);
    for (const Vec3& d : directions) {
        Rgb color;
        int storeTexel = -1;
        EXPECT_TRUE(lookUp(d, spreadAllowing(2, 64), color, storeTexel));
    }
    // Up to 1 % of the lookups (2 of 203) may want a finer cube; 3 do: it
    // goes back to 64² at once.
    for (int i = 0; i < 3; ++i) {
        Rgb color;
        int storeTexel = -1;
        lookUp(directions[static_cast<std::size_t>(i)], 0.0f, color, storeTexel);
    }
    stats = cache.endFrame(workers);
    EXPECT_EQ(stats.objects[0].resizedTo, 64);
    ASSERT_EQ(cache.cube(0).size(), 64);

    // Frame 3: an inherited colour answers a footprint two levels wide, at
    // level 2, and not a narrow one, whose store then replaces it.
    cache.beginFrame(workers);
    workers[0].beginBatch(0);
    const Vec3 d = directions[0];
    const int texel = cache.cube(0).texelIndexFor(d);
    ASSERT_EQ(cache.cube(0).inheritedLevels(texel), 2);
    Rgb color;
    int storeTexel = -1;
    EXPECT_TRUE(lookUp(d, spreadAllowing(2, 64), color, storeTexel));
    EXPECT_EQ(storeTexel, -1);
    EXPECT_FALSE(lookUp(d, spreadAllowing(1, 64), color, storeTexel));
    EXPECT_EQ(storeTexel, texel);
    cache.store(0, d * 1.001f, d, Rgb{0, 1, 0}, 3.0f, workers[0], storeTexel);
    stats = cache.endFrame(workers);
    EXPECT_EQ(stats.objects[0].hitsByLevel[2], 1u);
    EXPECT_EQ(stats.objects[0].stores, 1u);
    EXPECT_EQ(cache.cube(0).inheritedLevels(texel), 0);
    EXPECT_EQ(CachingCube::encodeTexel(*cache.cube(0).read(texel)), CachingCube::encodeTexel(Rgb{0, 1, 0}));
}

TEST(ViewSizedCube, FirstFrameEqualsTheUncachedRenderAndCubesShrink) {
    // grid-8's mirrors at 96² pixels are a few pixels wide: 512² faces are far
    // finer than their footprints.
    const PathRender sized = renderPath("grid-8", CacheTechnique::Cct, 1, true, 96, 2, 512, nullptr,
                                        TileBalance::Dynamic, 1, 0, true);
    const PathRender plain = renderPath("grid-8", CacheTechnique::None, 1, true, 96);
    ASSERT_EQ(sized.frames.size(), 1u);
    EXPECT_EQ(sized.frames[0].pixels(), plain.frames[0].pixels());
    ASSERT_TRUE(sized.stats[0].cache);
    for (const ObjectCacheStats& o : sized.stats[0].cache->objects) {
        EXPECT_GT(o.resizedTo, 0) << o.name;
        EXPECT_LT(o.resizedTo, 512) << o.name;
    }
}

TEST(ViewSizedCube, ImagesAndCubesBitIdenticalAcrossThreadCounts) {
    const PathRender one = renderPath("grid-8", CacheTechnique::Cct, 4, false, 96, 1, 256, nullptr,
                                      TileBalance::Dynamic, 1, 0, true);
    for (const int threads : {2, 3}) {
        const PathRender many = renderPath("grid-8", CacheTechnique::Cct, 4, false, 96, threads, 256, nullptr,
                                           TileBalance::Dynamic, 1, 0, true);
        ASSERT_EQ(one.frames.size(), many.frames.size());
        for (std::size_t f = 0; f < one.frames.size(); ++f)
            EXPECT_EQ(one.frames[f].pixels(), many.frames[f].pixels()) << "frame " << f << ", " << threads << " threads";
        EXPECT_EQ(one.texels, many.texels) << threads << " threads";
    }
}

TEST(ViewSizedCube, ClearingStartsAgainAtTheFullResolution) {
    RayCacheSettings settings;
    settings.resolutionFromView = true;
    settings.levelErrorBound = 1.0f;
    RayCache cache(oneCctMirror(64), settings);
    auto workers = cache.makeWorkers(1);
    cache.beginFrame(workers);
    workers[0].beginBatch(0);
    const Vec3 d = normalize(Vec3{1, 2, 3});
    const RayCache::Query q{0, d * 1.001f, d, spreadAllowing(2, 64)};
    Rgb color;
    unsigned char found = 0;
    int storeTexel = -1;
    cache.lookupBatch(std::span(&q, 1), std::span(&color, 1), std::span(&found, 1), std::span(&storeTexel, 1), workers[0]);
    cache.store(0, q.origin, d, Rgb{1, 0, 0}, 3.0f, workers[0], storeTexel);
    cache.endFrame(workers);
    ASSERT_EQ(cache.cube(0).size(), 16);
    ASSERT_EQ(cache.cube(0).validCount(), 1u);
    cache.clear();
    EXPECT_EQ(cache.cube(0).size(), 64);
    EXPECT_EQ(cache.cube(0).validCount(), 0u);
}
