// Improved CDCT (technique `cdct`): the pre-fill protocol, the texel-space
// search with empty-space skipping against analytic surfaces, error control,
// termination on awkward rays, determinism, and the parallax quality margin
// over CCT with the uncached render as ground truth.
#include <gtest/gtest.h>

#include "CdctFixtures.h"
#include "PathRender.h"
#include "UnderSanitizers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "cache/CdctSearch.h"
#include "cache/DepthPyramid.h"
#include "cache/RayCache.h"
#include "metrics/ImageMetrics.h"

using namespace raycache;
using namespace raycache::cdct_test;

namespace {

Scene oneMirror(int resolution) { return cdct_test::oneMirror(CacheTechnique::Cdct, resolution); }

// Goes through the pre-fill protocol as a renderer does: a frame asks for the
// cube, then every texel gets colorOf(texel) at the distance `depthOf` gives
// for its direction (infinity: a miss).
// `sawMirror` (optional): whether the texel of a direction saw a mirror or
// glass (PrefillTexel::viewDependent).
void prefill(RayCache& cache, const std::function<float(const Vec3&)>& depthOf,
             const std::function<bool(const Vec3&)>& sawMirror = {}) {
    auto workers = cache.makeWorkers(1);
    cache.beginFrame(workers);
    workers[0].beginBatch(0);
    EXPECT_FALSE(cache.lookup(0, {0, 0, 1.001f}, {0, 0, 1}, workers[0]).has_value()) << "nothing cached yet";
    const std::vector<int> awaiting = cache.objectsAwaitingPrefill(workers);
    ASSERT_EQ(awaiting, std::vector<int>{0});
    std::vector<RayCache::PrefillTexel> texels(cache.cube(0).texelCount());
    for (std::size_t i = 0; i < texels.size(); ++i) {
        const Vec3 direction = cache.prefillDirection(0, static_cast<int>(i));
        EXPECT_NEAR(length(direction), 1.0f, 1e-5f);
        EXPECT_EQ(cache.cube(0).texelIndexFor(direction), static_cast<int>(i)) << "through the texel's centre";
        texels[i] = {colorOf(static_cast<int>(i)), depthOf(direction), sawMirror && sawMirror(direction) ? 1u : 0u};
    }
    cache.completePrefill(0, texels);
    const FrameCacheStats stats = cache.endFrame(workers);
    EXPECT_EQ(stats.objects[0].prefilledTexels, cache.cube(0).texelCount());
    EXPECT_EQ(cache.cube(0).validCount(), cache.cube(0).texelCount());
    EXPECT_TRUE(cache.objectsAwaitingPrefill(workers).empty());
}

// Every combination of the search's switches (pre-fill stays on: the tests
// fill the cube through it).
std::vector<CdctImprovements> searchVariants() {
    std::vector<CdctImprovements> variants;
    for (int bits = 0; bits < 16; ++bits) {
        CdctImprovements i;
        i.texelSteps = bits & 1;
        i.earlyExit = bits & 2;
        i.skipEmptySpace = bits & 4;
        i.filter = bits & 8;
        i.errorControl = true;
        variants.push_back(i);
    }
    return variants;
}

}  // namespace

TEST(CdctImproved, DepthPyramidHoldsTheMinimumOfEveryBlock) {
    RayCache cache(oneMirror(64), {});
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(1.5f, 90.0f);
    prefill(cache, [&](const Vec3&) { return uniform(random); });
    const CachingCube& cube = cache.cube(0);
    const DepthPyramid pyramid(cube);
    ASSERT_EQ(pyramid.levelCount(), 3);  // blocks of 4, 16, 64 texels
    for (int level = 0; level < pyramid.levelCount(); ++level) {
        const int side = pyramid.blockSide(level);
        for (int face = 0; face < 6; ++face)
            for (int by = 0; by < 64 / side; ++by)
                for (int bx = 0; bx < 64 / side; ++bx) {
                    float expected = kInf;
                    for (int y = by * side; y < (by + 1) * side; ++y)
                        for (int x = bx * side; x < (bx + 1) * side; ++x)
                            expected = std::min(expected,
                                                cube.depth(cubeTexelIndex({static_cast<CubeFace>(face), x, y}, 64)));
                    // Any texel of the block names the block.
                    EXPECT_EQ(pyramid.minDepth(level, face, bx * side + side - 1, by * side), expected);
                }
    }
}

TEST(CdctImproved, SearchFindsAnAnalyticSphereWithEverySwitchSetting) {
    // Every texel holds the surface of a sphere of radius 5 around the centre.
    for (const CdctImprovements& improvements : searchVariants()) {
        RayCacheSettings settings;
        settings.cdctImprovements = improvements;
        RayCache cache(oneMirror(64), settings);
        prefill(cache, [](const Vec3&) { return 5.0f; });
        const CachingCube& cube = cache.cube(0);
        auto workers = cache.makeWorkers(1);
        cache.beginFrame(workers);
        workers[0].beginBatch(0);
        for (const Probe& p : awkwardRays()) {
            const Vec3 d = normalize(p.direction);
            const float b = dot(p.origin, d);
            const Vec3 onSurface = p.origin + d * (-b + std::sqrt(b * b - dot(p.origin, p.origin) + 25.0f));
            const auto color = cache.lookup(0, p.origin, p.direction, workers[0]);
            ASSERT_TRUE(color.has_value()) << improvements.texelSteps << improvements.skipEmptySpace;
            if (improvements.filter) {
                // A blend of the texels around the hit: within the range of colours there.
                EXPECT_TRUE(color->isFinite());
                continue;
            }
            // The texel where the ray meets the sphere, or one next to it.
            bool near = false;
            for (float dt : {-0.08f, -0.04f, 0.0f, 0.04f, 0.08f})
                near = near || *color == colorOf(cube.texelIndexFor(onSurface + d * dt));
            EXPECT_TRUE(near) << p.direction.x << " " << p.direction.y << " " << p.direction.z << " steps "
                              << improvements.texelSteps << " skip " << improvements.skipEmptySpace;
        }
        const FrameCacheStats stats = cache.endFrame(workers);
        EXPECT_EQ(stats.objects[0].hits, awkwardRays().size());
        EXPECT_EQ(stats.objects[0].rejected, 0u);
    }
}

// The face walk (CdctImprovements::faceWalk) against a dense march (an
// oracle that knows nothing of faces, texel edges or the pyramid): along
// random rays through a blocky depth field, whose depth jumps from texel to
// texel, the first texel whose stored depth the ray reaches is the same.
// The march samples every 1e-4 of the way, so it may step over a corner a
// ray clips for less than that; such rays are counted and must stay rare.
// Under the sanitizers a quarter of the rays (tests/UnderSanitizers.h).
TEST(CdctImproved, FaceWalkMeetsTheTexelADenseMarchMeetsFirst) {
    RayCacheSettings settings;
    settings.cdctImprovements.errorControl = false;
    settings.cdctImprovements.filter = false;
    RayCache cache(oneMirror(32), settings);
    // Per texel a depth in [2, 5), from a hash of its index.
    const auto depthOfTexel = [](int texel) { return 2.0f + 3.0f * static_cast<float>((texel * 2654435761u) >> 22) / 1024.0f; };
    prefill(cache, [&](const Vec3& v) { return depthOfTexel(cache.cube(0).texelIndexFor(v)); });
    const CachingCube& cube = cache.cube(0);
    const DepthPyramid pyramid(cube);
    const CdctParameters parameters = RayCache::cdctParametersFor(oneMirror(32).objects[0], settings);
    std::mt19937 random(11);
    std::uniform_real_distribution<float> inside(-0.9f, 0.9f);
    int compared = 0, differing = 0;
    double walkSteps = 0.0;
    const int rays = test::kUnderSanitizers ? 100 : 400;
    for (int i = 0; i < rays; ++i) {
        const Vec3 origin{inside(random), inside(random), inside(random)};
        const Vec3 d = randomDirection(random);
        for (const bool skip : {false, true}) {
            CdctImprovements improvements = settings.cdctImprovements;
            improvements.skipEmptySpace = skip;
            const CdctResult walked =
                searchCdctImproved(cube, parameters, improvements, 5.0f, skip ? &pyramid : nullptr, origin, d);
            ASSERT_EQ(walked.outcome, CdctOutcome::Found) << i;
            walkSteps += walked.steps;
            int marched = -1;
            for (double t = 0.0; t < 10.0 && marched < 0; t += 1e-4) {
                const Vec3 p = origin + d * static_cast<float>(t);
                if (std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) < 1.0f) continue;  // inside the box
                const int texel = cube.texelIndexFor(p);
                if (cube.depth(texel) <= length(p)) marched = texel;
            }
            ASSERT_GE(marched, 0) << i;
            ++compared;
            if (walked.texel != marched) ++differing;
        }
    }
    std::printf("[face walk] %d of %d searches met another texel than the dense march; %.1f steps per search\n",
                differing, compared, walkSteps / compared);
    EXPECT_LE(differing, compared / 100);
}

// The cache counts every search's steps (the texels it sampled) into the
// frame's statistics: the same totals as calling the search directly, a
// histogram that sums to the searches, and skipping empty space must take
// fewer steps than marching texel by texel.
TEST(CdctImproved, SearchStepsAreCountedAndEmptySpaceSkippingSavesThem) {
    std::uint64_t stepsBySkipping[2] = {0, 0};
    for (const bool skip : {false, true}) {
        RayCacheSettings settings;
        settings.cdctImprovements.skipEmptySpace = skip;
        RayCache cache(oneMirror(64), settings);
        prefill(cache, [](const Vec3&) { return 5.0f; });
        const CachingCube& cube = cache.cube(0);
        const DepthPyramid pyramid(cube);
        const CdctParameters parameters = RayCache::cdctParametersFor(oneMirror(64).objects[0], settings);
        auto workers = cache.makeWorkers(1);
        cache.beginFrame(workers);
        workers[0].beginBatch(0);
        std::uint64_t direct = 0;
        for (const Probe& p : awkwardRays()) {
            const CdctResult r = searchCdctImproved(cube, parameters, settings.cdctImprovements, 5.0f,
                                                    skip ? &pyramid : nullptr, p.origin, p.direction);
            EXPECT_GE(r.steps, 1);
            direct += static_cast<std::uint64_t>(r.steps);
            cache.lookup(0, p.origin, p.direction, workers[0]);
        }
        const FrameCacheStats stats = cache.endFrame(workers);
        const ObjectCacheStats& o = stats.objects[0];
        EXPECT_EQ(o.cdctSearches, awkwardRays().size());
        EXPECT_EQ(o.cdctSteps, direct);
        std::uint64_t histogram = 0;
        for (const std::uint64_t n : o.cdctStepsHistogram) histogram += n;
        EXPECT_EQ(histogram, o.cdctSearches);
        stepsBySkipping[skip] = o.cdctSteps;
    }
    EXPECT_LT(stepsBySkipping[1], stepsBySkipping[0]);
    EXPECT_EQ(cdctStepBucket(3), 0);
    EXPECT_EQ(cdctStepBucket(4), 1);
    EXPECT_EQ(cdctStepBucket(1023), 4);
    EXPECT_EQ(cdctStepBucket(1u << 20), kCdctStepBuckets - 1);
}

TEST(CdctImproved, EnvironmentBeyondTheFarthestSurfaceIsAnsweredFromMaxDepth) {
    // Upper half: a surface at distance 3; lower half: nothing (environment).
    for (bool earlyExit : {false, true}) {
        RayCacheSettings settings;
        settings.cdctImprovements.earlyExit = earlyExit;
        settings.cdctImprovements.filter = false;
        RayCache cache(oneMirror(32), settings);
        prefill(cache, [](const Vec3& v) { return v.y > 0.0f ? 3.0f : kInf; });
        auto workers = cache.makeWorkers(1);
        cache.beginFrame(workers);
        workers[0].beginBatch(0);
        const Vec3 origin{0, -1.0001f, 0}, direction = normalize(Vec3{0.3f, -1.0f, 0.2f});
        const auto color = cache.lookup(0, origin, direction, workers[0]);
        ASSERT_TRUE(color.has_value()) << earlyExit;
        // The texel of the ray's point 100 (maxDepth) from the centre.
        const float t = rayParameterAtDistance({0, 0, 0}, origin, direction, 100.0f);
        EXPECT_EQ(*color, colorOf(cache.cube(0).texelIndexFor(origin + direction * t))) << earlyExit;
        cache.endFrame(workers);
    }
}

TEST(CdctImproved, ErrorControlRejectsAFoundTexelOffTheRay) {
    // A near wall (distance 2) fills the directions with x > 0.5 |v|; the
    // rest holds a far surface (distance 8). The probe enters the wall's
    // directions already 5 units out, behind the wall as seen from the
    // centre: the search stops at the wall's edge, whose stored point lies
    // 0.37 units off the ray, far beyond 2 texel footprints (2 * 2 * 2 / 64).
    const auto depthOf = [](const Vec3& v) { return v.x > 0.5f * length(v) ? 2.0f : 8.0f; };
    const Vec3 origin{0, 1.01f, 0}, direction{0.6f, 0.8f, 0.0f};
    for (bool errorControl : {true, false}) {
        RayCacheSettings settings;
        settings.cdctImprovements.errorControl = errorControl;
        settings.cdctImprovements.filter = false;
        RayCache cache(oneMirror(64), settings);
        prefill(cache, depthOf);
        auto workers = cache.makeWorkers(1);
        cache.beginFrame(workers);
        workers[0].beginBatch(0);
        const auto color = cache.lookup(0, origin, direction, workers[0]);
        const FrameCacheStats stats = cache.endFrame(workers);
        if (errorControl) {
            EXPECT_FALSE(color.has_value()) << "traced instead";
            EXPECT_EQ(stats.objects[0].rejected, 1u);
            EXPECT_EQ(stats.objects[0].misses, 1u);
        } else {
            // Without it the wall's colour is returned: a texel whose direction has x > 0.5.
            ASSERT_TRUE(color.has_value());
            bool wall = false;
            for (int i = 0; i < static_cast<int>(cache.cube(0).texelCount()); ++i)
                if (*color == colorOf(i)) wall = wall || depthOf(cache.prefillDirection(0, i)) == 2.0f;
            EXPECT_TRUE(wall);
            EXPECT_EQ(stats.objects[0].rejected, 0u);
        }
    }
}

TEST(CdctImproved, AwkwardRaysAndExtremeParametersTerminate) {
    RayCacheSettings settings;
    settings.cdctStepOverride = 0.2f;  // the fixed-step variants: 1e6 steps to maxDepth, the limit
    settings.cdctEpsilonOverride = 1e-9f;
    settings.cdctMaxDepthOverride = 1e5f;
    settings.cdctToleranceOverride = 1e6f;
    const std::vector<std::function<float(const Vec3&)>> surfaces{
        [](const Vec3&) { return kInf; },                                      // nothing at all
        [](const Vec3& v) { return v.x > 0.0f ? 1.5f : 1e5f; },               // a discontinuity
        [](const Vec3& v) { return 1.2f + 50.0f * std::fabs(v.y) / length(v); }};  // steep slopes
    for (const auto& surface : surfaces) {
        for (const CdctImprovements& improvements : searchVariants()) {
            settings.cdctImprovements = improvements;
            RayCache cache(oneMirror(32), settings);
            prefill(cache, surface);
            auto workers = cache.makeWorkers(1);
            cache.beginFrame(workers);
            workers[0].beginBatch(0);
            for (const Probe& p : awkwardRays()) {
                if (const auto color = cache.lookup(0, p.origin, p.direction, workers[0])) {
                    EXPECT_TRUE(color->isFinite());
                }
            }
            // Degenerate input never reaches the cube.
            EXPECT_FALSE(cache.lookup(0, {0, 0, 1}, {0, 0, 0}, workers[0]).has_value());
            EXPECT_FALSE(cache.lookup(0, {0, 0, kInf}, {0, 0, 1}, workers[0]).has_value());
            EXPECT_FALSE(cache.lookup(0, {0, 0, 1}, {std::nanf(""), 0, 1}, workers[0]).has_value());
            cache.endFrame(workers);
        }
    }
}

TEST(CdctImproved, FirstFrameTracesThenPrefillsThenAnswers) {
    const PathRender run = renderPath("parallax", CacheTechnique::Cdct, 3, true, 96, 2, 32);
    const PathRender plain = renderPath("parallax", CacheTechnique::None, 1, true, 96, 2, 32);
    ASSERT_EQ(run.stats.size(), 3u);
    EXPECT_TRUE(identicalImages(run.frames[0], plain.frames[0])) << "frame 1 traces every ray";
    EXPECT_EQ(run.stats[0].cache->hits(), 0u);
    EXPECT_EQ(run.stats[0].cache->cdctSearches(), 0u) << "nothing searched before the pre-fill";
    EXPECT_EQ(run.stats[1].cache->cdctSearches(), run.stats[1].cache->lookups()) << "every lookup searched after it";
    EXPECT_GT(run.stats[1].cache->cdctSteps(), run.stats[1].cache->cdctSearches());
    EXPECT_EQ(run.stats[0].cache->prefilledTexels(), 2u * 6u * 32u * 32u) << "both mirrors, after frame 1";
    EXPECT_EQ(run.stats[0].rays.prefill, 2u * 6u * 32u * 32u);
    EXPECT_EQ(run.stats[1].cache->prefilledTexels(), 0u);
    EXPECT_EQ(run.stats[1].cache->invalidPercentBefore(), 0.0);
    EXPECT_GT(run.stats[1].cache->hits(), run.stats[1].cache->lookups() * 9 / 10) << "most lookups answered";
    EXPECT_LT(run.stats[1].rays.reflection, run.stats[0].rays.reflection / 5);
}

TEST(CdctImproved, ImagesAndCachesBitIdenticalAcrossThreadCounts) {
    const PathRender one = renderPath("parallax", CacheTechnique::Cdct, 3, false, 96, 1, 32);
    const PathRender three = renderPath("parallax", CacheTechnique::Cdct, 3, false, 96, 3, 32);
    ASSERT_EQ(one.frames.size(), three.frames.size());
    for (std::size_t f = 0; f < one.frames.size(); ++f)
        EXPECT_TRUE(identicalImages(one.frames[f], three.frames[f])) << "frame " << f;
    EXPECT_EQ(one.texels, three.texels);
    EXPECT_GT(one.stats.back().cache->hits(), 0u);
}

TEST(CdctImproved, ParallaxCloserToUncachedThanCctAlongTheCameraPath) {
    // The parallax scene's camera slides sideways: CCT, which takes every
    // reflected ray to start at the mirror's centre, shows the near box and
    // the wall in the wrong places; CDCT finds them along the actual ray.
    // Mean PSNR over frames 2..25 (frame 1 traces everything in both), 256x256
    // image, 64x64 faces (CCT then answers most of its lookups). Measured
    // 2026-11-21: CCT 22.18 dB (88% hits), CDCT 27.73 dB: +5.55 dB. The
    // threshold is that margin, rounded down to 5 dB; the goal was 3 dB.
    constexpr int kFrames = 25;  // the whole path
    const PathRender plain = renderPath("parallax", CacheTechnique::None, kFrames, false, 256, 2, 64);
    const PathRender cct = renderPath("parallax", CacheTechnique::Cct, kFrames, false, 256, 2, 64);
    const PathRender cdct = renderPath("parallax", CacheTechnique::Cdct, kFrames, false, 256, 2, 64);
    std::uint64_t cctHits = 0, cctLookups = 0;
    double cctSum = 0.0, cdctSum = 0.0;
    for (int f = 1; f < kFrames; ++f) {
        const auto i = static_cast<std::size_t>(f);
        EXPECT_EQ(countNonFinitePixels(cdct.frames[i]), 0);
        cctSum += psnr(cct.frames[i], plain.frames[i]);
        cctHits += cct.stats[i].cache->hits();
        cctLookups += cct.stats[i].cache->lookups();
        cdctSum += psnr(cdct.frames[i], plain.frames[i]);
        EXPECT_GT(cdct.stats[i].cache->hits(), cdct.stats[i].cache->lookups() * 9 / 10) << "frame " << f;
    }
    const double cctDb = cctSum / (kFrames - 1), cdctDb = cdctSum / (kFrames - 1);
    std::printf("parallax 256x256, 64^2 faces, frames 2-%d: CCT %.2f dB (hits %.0f%%), CDCT %.2f dB (+%.2f dB)\n",
                kFrames, cctDb, 100.0 * static_cast<double>(cctHits) / static_cast<double>(cctLookups), cdctDb,
                cdctDb - cctDb);
    // The comparison means something only if CCT answers most of its lookups too.
    EXPECT_GT(cctHits, cctLookups * 3 / 4);
    RecordProperty("cct_psnr_db", std::to_string(cctDb));
    RecordProperty("cdct_psnr_db", std::to_string(cdctDb));
    EXPECT_GE(cdctDb - cctDb, 5.0);
}

TEST(CdctImproved, TexelsThatSawAMirrorFromTheCentreAreTracedNotAnswered) {
    // Every direction met a surface 3 from the centre; those above the
    // equator met a mirror, whose colour as seen from the centre is not
    // what a ray from elsewhere on the object sees.
    for (const bool trace : {false, true}) {
        RayCacheSettings settings;
        settings.cdctImprovements.traceViewDependent = trace;
        RayCache cache(oneMirror(32), settings);
        prefill(cache, [](const Vec3&) { return 3.0f; }, [](const Vec3& v) { return v.y > 0.0f; });
        auto workers = cache.makeWorkers(1);
        cache.beginFrame(workers);
        workers[0].beginBatch(0);
        const auto up = cache.lookup(0, {0, 1.0001f, 0}, normalize(Vec3{0.2f, 1.0f, 0.1f}), workers[0]);
        const auto down = cache.lookup(0, {0, -1.0001f, 0}, normalize(Vec3{0.2f, -1.0f, 0.1f}), workers[0]);
        EXPECT_TRUE(down.has_value()) << trace;
        EXPECT_EQ(up.has_value(), !trace);
        const FrameCacheStats stats = cache.endFrame(workers);
        EXPECT_EQ(stats.objects[0].viewDependent, trace ? 1u : 0u);
        EXPECT_EQ(stats.objects[0].misses, trace ? 1u : 0u);
        EXPECT_EQ(stats.objects[0].cdctSearches, 2u) << "the texel is known only once the search found it";
    }
}

TEST(CdctImproved, QueriesMeetingTheirOwnObjectAreMissesWithoutASearch) {
    RayCache cache(oneMirror(32), {});
    EXPECT_TRUE(cache.seesPastOwnSurface(0)) << "the pre-fill passes through the object's own surface";
    EXPECT_EQ(cache.objectsSeenPastThemselves(), std::vector<int>{0});
    prefill(cache, [](const Vec3&) { return 3.0f; });
    auto workers = cache.makeWorkers(1);
    cache.beginFrame(workers);
    workers[0].beginBatch(0);
    const Vec3 origin{0, 0, 1.0001f}, direction = normalize(Vec3{0.1f, 0.2f, 1.0f});
    const std::vector<RayCache::Query> queries{{0, origin, direction, 0.0f, false}, {0, origin, direction, 0.0f, true}};
    std::vector<Rgb> colors(2);
    std::vector<unsigned char> found(2);
    std::vector<int> storeTexels(2);
    cache.lookupBatch(queries, colors, found, storeTexels, workers[0]);
    EXPECT_EQ(found[0], 1);
    EXPECT_EQ(found[1], 0) << "the cube holds what lies behind the object's surface, not the surface";
    const FrameCacheStats stats = cache.endFrame(workers);
    EXPECT_EQ(stats.objects[0].ownSurface, 1u);
    EXPECT_EQ(stats.objects[0].misses, 1u);
    EXPECT_EQ(stats.objects[0].cdctSearches, 1u);

    // Cubes that hold the object's own surface, or that are told not to test it.
    RayCacheSettings off;
    off.cdctImprovements.traceOwnSurface = false;
    EXPECT_FALSE(RayCache(oneMirror(32), off).seesPastOwnSurface(0));
    EXPECT_TRUE(RayCache(oneMirror(32), off).objectsSeenPastThemselves().empty());
    EXPECT_FALSE(RayCache(cdct_test::oneMirror(CacheTechnique::CdctParity, 32), {}).seesPastOwnSurface(0));
    EXPECT_FALSE(RayCache(cdct_test::oneMirror(CacheTechnique::Cct, 32), {}).seesPastOwnSurface(0));
}
