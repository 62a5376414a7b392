#include <gtest/gtest.h>

#include <limits>

#include "cache/RayCache.h"
#include "core/Errors.h"

using namespace raycache;

namespace {

Scene twoMirrorsAndAMatte() {
    Scene s;
    Material mirror;
    mirror.reflectivity = 0.8f;
    mirror.cache = {CacheTechnique::Cct, 16};
    Material matte;
    matte.cache = {CacheTechnique::Cct, 16};  // caching is ignored on objects that neither reflect nor refract
    s.objects.push_back(SceneObject{"a", Sphere{{0, 0, 0}, 1}, mirror, {0, 0, 0}});
    s.objects.push_back(SceneObject{"b", Sphere{{5, 0, 0}, 1}, matte, {5, 0, 0}});
    mirror.cache.technique = CacheTechnique::None;
    s.objects.push_back(SceneObject{"c", Sphere{{-5, 0, 0}, 1}, mirror, {-5, 0, 0}});
    return s;
}

}  // namespace

TEST(RayCache, CubesOnlyForReflectiveOrRefractiveObjectsThatAskForThem) {
    const RayCache cache(twoMirrorsAndAMatte(), {});
    EXPECT_TRUE(cache.cachesObject(0));
    EXPECT_FALSE(cache.cachesObject(1));
    EXPECT_FALSE(cache.cachesObject(2));
    EXPECT_EQ(cache.bytes(), 6u * 16u * 16u * 4u);

    RayCacheSettings all;
    all.techniqueOverride = CacheTechnique::Cct;
    all.resolutionOverride = 32;
    const RayCache overridden(twoMirrorsAndAMatte(), all);
    EXPECT_TRUE(overridden.cachesObject(2));
    EXPECT_FALSE(overridden.cachesObject(1));
    EXPECT_EQ(overridden.cube(2).size(), 32);

    RayCacheSettings none;
    none.techniqueOverride = CacheTechnique::None;
    EXPECT_TRUE(RayCache(twoMirrorsAndAMatte(), none).empty());
}

TEST(RayCache, RejectsBadResolutionsAndCdctParameters) {
    RayCacheSettings tiny;
    tiny.resolutionOverride = 8;
    EXPECT_THROW(RayCache(twoMirrorsAndAMatte(), tiny), InputError);
    RayCacheSettings huge;
    huge.resolutionOverride = 4096;
    EXPECT_THROW(RayCache(twoMirrorsAndAMatte(), huge), InputError);
    RayCacheSettings cdct;
    cdct.techniqueOverride = CacheTechnique::Cdct;
    EXPECT_NO_THROW(RayCache(twoMirrorsAndAMatte(), cdct));
    for (float bad : {0.0f, -1.0f, std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
        RayCacheSettings s = cdct;
        s.cdctStepOverride = bad;
        EXPECT_THROW(RayCache::validate(twoMirrorsAndAMatte(), s), InputError) << bad;
        s = cdct;
        s.cdctEpsilonOverride = bad;
        EXPECT_THROW(RayCache::validate(twoMirrorsAndAMatte(), s), InputError) << bad;
        s = cdct;
        s.cdctMaxDepthOverride = bad;
        EXPECT_THROW(RayCache::validate(twoMirrorsAndAMatte(), s), InputError) << bad;
    }
    RayCacheSettings epsilonNotBelowStep = cdct;
    epsilonNotBelowStep.cdctStepOverride = 0.1f;
    epsilonNotBelowStep.cdctEpsilonOverride = 0.1f;
    EXPECT_THROW(RayCache::validate(twoMirrorsAndAMatte(), epsilonNotBelowStep), InputError);
    RayCacheSettings tooManySteps = cdct;
    tooManySteps.cdctStepOverride = 1e-3f;
    tooManySteps.cdctEpsilonOverride = 1e-4f;
    tooManySteps.cdctMaxDepthOverride = 1e6f;
    EXPECT_THROW(RayCache::validate(twoMirrorsAndAMatte(), tooManySteps), InputError);
    // Parameters of objects that are not cached with CDCT are not checked.
    RayCacheSettings cct;
    cct.cdctStepOverride = -1.0f;
    EXPECT_NO_THROW(RayCache::validate(twoMirrorsAndAMatte(), cct));
}

TEST(RayCache, CdctCubesKeepADepthPerTexelAndABoundingBox) {
    RayCacheSettings cdct;
    cdct.techniqueOverride = CacheTechnique::Cdct;
    const RayCache cache(twoMirrorsAndAMatte(), cdct);
    ASSERT_TRUE(cache.cachesObject(0));
    EXPECT_TRUE(cache.cube(0).hasDepth());
    EXPECT_EQ(cache.bytes(), 2u * 6u * 16u * 16u * 8u);  // objects a and c, 8 bytes per texel
    EXPECT_EQ(cache.cube(0).depthWords().size(), 6u * 16u * 16u);
    EXPECT_EQ(cache.cube(0).depth(0), CachingCube::kInvalidDepth);
    const Vec3 half = cache.cube(0).halfSize();
    EXPECT_NEAR(half.x, 1.0f, 0.01f);
    EXPECT_GE(half.x, 1.0f);
    EXPECT_NEAR(half.y, 1.0f, 0.01f);
    EXPECT_NEAR(half.z, 1.0f, 0.01f);
    EXPECT_FALSE(RayCache(twoMirrorsAndAMatte(), {}).cube(0).hasDepth());
}

TEST(RayCache, LookupsSeeTheFrameStartStateAndTheLowestPixelWins) {
    RayCache cache(twoMirrorsAndAMatte(), {});
    const Vec3 p{0, 0, 1}, d{0.1f, 0.2f, 1.0f};
    // Two workers store into the same texel; which worker runs first must not matter.
    for (bool reversed : {false, true}) {
        cache.clear();
        auto workers = cache.makeWorkers(2);
        cache.beginFrame(workers);
        CacheWorker& first = workers[reversed ? 1 : 0];
        CacheWorker& second = workers[reversed ? 0 : 1];
        second.beginBatch(900);
        EXPECT_FALSE(cache.lookup(0, p, d, second).has_value());
        cache.store(0, p, d, Rgb{0.25f}, 3.0f, second);
        first.beginBatch(12);
        EXPECT_FALSE(cache.lookup(0, p, d, first).has_value());  // not visible before the frame ends
        cache.store(0, p, d, Rgb{0.5f}, 3.0f, first);
        const FrameCacheStats stats = cache.endFrame(workers);
        ASSERT_EQ(stats.objects.size(), 1u);
        EXPECT_EQ(stats.objects[0].lookups, 2u);
        EXPECT_EQ(stats.objects[0].misses, 2u);
        EXPECT_EQ(stats.objects[0].stores, 1u);
        EXPECT_DOUBLE_EQ(stats.objects[0].invalidPercentBefore, 100.0);

        cache.beginFrame(workers);
        workers[0].beginBatch(0);
        const auto hit = cache.lookup(0, p, d, workers[0]);
        ASSERT_TRUE(hit.has_value());
        EXPECT_EQ(*hit, Rgb{0.5f}) << "pixel 12 precedes pixel 900";
        const FrameCacheStats next = cache.endFrame(workers);
        EXPECT_EQ(next.objects[0].hits, 1u);
        EXPECT_LT(next.objects[0].invalidPercentBefore, 100.0);
    }
}

TEST(RayCache, IdealModeAnswersMissesWithBlackWithoutStoring) {
    RayCacheSettings ideal;
    ideal.ideal = true;
    RayCache cache(twoMirrorsAndAMatte(), ideal);
    auto workers = cache.makeWorkers(1);
    cache.beginFrame(workers);
    workers[0].beginBatch(0);
    const auto answer = cache.lookup(0, {0, 0, 1}, {0, 0, 1}, workers[0]);
    ASSERT_TRUE(answer.has_value());
    EXPECT_EQ(*answer, Rgb{0.0f});
    EXPECT_EQ(cache.endFrame(workers).objects[0].misses, 1u);
}
