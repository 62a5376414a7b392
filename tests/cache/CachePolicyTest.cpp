// The cache policy (cache/CachePolicy.h): its decision on constructed counts,
// and renders that step cubes aside checked against their ground truth, the
// uncached render.
#include <gtest/gtest.h>

#include "ImageCompare.h"
#include "PathRender.h"

#include <cstring>

#include "cache/CachePolicy.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

const CachePolicyCosts kPolicyTestCosts{0.1, 0.1, 0.02};

// A frame of `lookups` lookups of which `hits` hit, the misses each traced a
// tree of `tree` rays and queued a store.
CubeFrameCounts policyFrame(std::uint64_t lookups, std::uint64_t hits, std::uint64_t tree) {
    const std::uint64_t misses = lookups - hits;
    return {lookups, hits, misses, misses, misses * tree, 0};
}

// A CCT cube under costs no hit repays: frame 0 fills its sample (not judged),
// frame 1 samples and loses, frames 2 to 1 + kFirstBackoff stand aside, the
// next two probe on the sample (the second judged, loses), then twice as
// many stand aside.
bool bypassedFrame(int f) { return (f >= 2 && f < 2 + CubePolicy::kFirstBackoff) || f >= 4 + CubePolicy::kFirstBackoff; }
bool samplingFrame(int f) { return f < 2 || f == 2 + CubePolicy::kFirstBackoff || f == 3 + CubePolicy::kFirstBackoff; }

// Costs no hit can repay: every judged frame loses.
CachePolicyCosts losingCosts() { return {1e6, 1e6, 1e6}; }

// An animated scene's settings, 48², two threads, CCT on 64² faces under
// `auto` with costs no hit repays.
RenderSettings losingAnimatedSettings() {
    RenderSettings settings;
    settings.width = settings.height = 48;
    settings.threads = 2;
    settings.cache.techniqueOverride = CacheTechnique::Cct;
    settings.cache.resolutionOverride = 64;
    settings.cache.policy = CachePolicyMode::Auto;
    settings.cache.policyCosts = losingCosts();
    return settings;
}

}  // namespace

// The names --cache-policy takes, in the order its message lists them.
TEST(CachePolicy, NamesItsModes) {
    ASSERT_EQ(kCachePolicyModes.size(), 2u);
    EXPECT_EQ(kCachePolicyModes[0], CachePolicyMode::Auto);
    EXPECT_STREQ(cachePolicyModeName(CachePolicyMode::Auto), "auto");
    EXPECT_STREQ(cachePolicyModeName(CachePolicyMode::Always), "always");
}

TEST(CachePolicy, FirstFrameFillsAndIsNotJudged) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    const auto j = p.afterFrame(policyFrame(1000, 0, 3));  // all misses: only cost
    EXPECT_FALSE(j.judged);
    EXPECT_GT(j.cost, j.saving);
    EXPECT_FALSE(p.bypassed());
}

TEST(CachePolicy, BypassesWhenCostsExceedSavings) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame(policyFrame(1000, 0, 3));
    // 10 hits of 3-ray trees save 30; 1000 lookups and 990 stores cost 199.
    const auto j = p.afterFrame(policyFrame(1000, 10, 3));
    EXPECT_TRUE(j.judged);
    EXPECT_DOUBLE_EQ(j.saving, 30.0);
    EXPECT_DOUBLE_EQ(j.cost, 1000 * 0.1 + 990 * 0.1);
    EXPECT_TRUE(p.bypassed());
}

TEST(CachePolicy, KeepsCachingWhenHitsPay) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame(policyFrame(1000, 0, 3));
    // A still camera's second frame: every lookup hits; the tree a hit
    // replaces is the last traced one's (3 rays).
    const auto j = p.afterFrame(policyFrame(1000, 1000, 3));
    EXPECT_TRUE(j.judged);
    EXPECT_DOUBLE_EQ(j.saving, 3000.0);
    EXPECT_FALSE(p.bypassed());
    EXPECT_DOUBLE_EQ(p.meanTree(), 3.0);
}

// The saving must beat the cost by CubePolicy::kSavingMargin (1.44), the
// one unit's error across scenes: at 1.4 times the cost the cube stands
// aside, at 1.5 times it caches.
TEST(CachePolicy, ASavingWithinTheMarginStandsAside) {
    ASSERT_DOUBLE_EQ(CubePolicy::kSavingMargin, 1.44);
    // Ten lookups at 1.0, all hits; a hit spares 1.4 or 1.5 rays.
    const auto allHits = [](std::uint64_t recordedHits, std::uint64_t recordedHitRays) {
        CubeFrameCounts counts = policyFrame(10, 10, 1);
        counts.recordedHits = recordedHits;
        counts.recordedHitRays = recordedHitRays;
        return counts;
    };
    CubePolicy within(CachePolicyMode::Auto, {1.0, 0.0, 0.0});
    within.afterFrame(policyFrame(10, 0, 1));
    const auto j = within.afterFrame(allHits(5, 7));
    EXPECT_DOUBLE_EQ(j.saving, 14.0);
    EXPECT_DOUBLE_EQ(j.cost, 10.0);
    EXPECT_TRUE(within.bypassed());
    CubePolicy past(CachePolicyMode::Auto, {1.0, 0.0, 0.0});
    past.afterFrame(policyFrame(10, 0, 1));
    EXPECT_DOUBLE_EQ(past.afterFrame(allHits(2, 3)).saving, 15.0);
    EXPECT_FALSE(past.bypassed());
}

TEST(CachePolicy, AlwaysNeverBypasses) {
    CubePolicy p(CachePolicyMode::Always, kPolicyTestCosts);
    for (int f = 0; f < 10; ++f) p.afterFrame(policyFrame(1000, 0, 3));
    EXPECT_FALSE(p.bypassed());
    EXPECT_EQ(p.framesCaching(), 10u);
    EXPECT_EQ(p.framesBypassed(), 0u);
}

TEST(CachePolicy, ProbesAfterABackoffThatDoublesUpToItsLongest) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame(policyFrame(1000, 0, 3));  // warm-up
    int expected = CubePolicy::kFirstBackoff;
    for (int probe = 0; probe < 8; ++probe) {
        p.afterFrame(policyFrame(1000, 0, 3));  // caching (a probe after the first) that loses
        ASSERT_TRUE(p.bypassed());
        for (int f = 0; f < expected; ++f) {
            ASSERT_TRUE(p.bypassed()) << "probe " << probe << " frame " << f;
            const auto j = p.afterFrame({});  // a bypassed frame counts nothing
            EXPECT_FALSE(j.judged);
        }
        EXPECT_FALSE(p.bypassed()) << "the next frame probes";
        expected = std::min(2 * expected, CubePolicy::kLongestBackoff);
    }
    EXPECT_EQ(expected, CubePolicy::kLongestBackoff);
}

TEST(CachePolicy, ResumesWhenAProbePaysAndTheBackoffStartsAgain) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame(policyFrame(1000, 0, 3));
    constexpr int kFirst = CubePolicy::kFirstBackoff;
    p.afterFrame(policyFrame(1000, 0, 3));  // loses: bypass kFirst
    for (int f = 0; f < kFirst; ++f) p.afterFrame({});
    p.afterFrame(policyFrame(1000, 0, 3));  // the probe loses: bypass 2 kFirst
    EXPECT_EQ(p.nextBackoff(), 4 * kFirst);
    for (int f = 0; f < 2 * kFirst; ++f) p.afterFrame({});
    ASSERT_FALSE(p.bypassed());
    p.afterFrame(policyFrame(1000, 900, 3));  // the probe pays: caching again
    EXPECT_FALSE(p.bypassed());
    EXPECT_EQ(p.nextBackoff(), kFirst);
    EXPECT_EQ(p.framesBypassed(), static_cast<std::uint64_t>(3 * kFirst));
    EXPECT_EQ(p.framesCaching(), 4u);
}

TEST(CachePolicy, HitsAreValuedByTheTreesTheirRecordedTexelsHeld) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame(policyFrame(100, 0, 10));  // misses' trees: 10 rays each
    // 60 hits; the 4 on sampled texels that recorded their trees found trees
    // of 2 rays (rays to the sky and their shadow ray): each hit spares 2,
    // not the misses' 10.
    CubeFrameCounts counts = policyFrame(100, 60, 10);
    counts.recordedHits = 4;
    counts.recordedHitRays = 8;
    const auto j = p.afterFrame(counts);
    EXPECT_DOUBLE_EQ(j.saving, 60 * 2.0);
    // A later frame without recorded hits (caching in full) keeps the value.
    EXPECT_DOUBLE_EQ(p.afterFrame(policyFrame(100, 50, 10)).saving, 50 * 2.0);
    EXPECT_DOUBLE_EQ(p.hitValue(), 2.0);
}

TEST(CachePolicy, NoEvidenceOfTreesCountsAHitAsOneRay) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame({100, 100, 0, 0, 0, 0});  // filled from elsewhere: no traced tree yet
    const auto j = p.afterFrame({100, 100, 0, 0, 0, 0});
    EXPECT_DOUBLE_EQ(j.saving, 100.0 * CachePolicyCosts::kMinimumTree);
    EXPECT_FALSE(p.bypassed());
}

TEST(CachePolicy, EmptiedCubeStartsOverAsItWasMade) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts, true);
    p.afterFrame(policyFrame(100, 0, 3));
    p.afterFrame(policyFrame(100, 100, 3));  // the sample pays: caching
    ASSERT_EQ(p.state(), CubeState::Caching);
    p.restart();
    EXPECT_EQ(p.state(), CubeState::Sampling);
    EXPECT_FALSE(p.afterFrame(policyFrame(100, 0, 3)).judged);
    CubePolicy aside(CachePolicyMode::Auto, kPolicyTestCosts, true);
    aside.afterFrame(policyFrame(100, 0, 3));
    aside.afterFrame(policyFrame(100, 0, 3));  // loses: stands aside
    ASSERT_TRUE(aside.bypassed());
    aside.restart();
    EXPECT_EQ(aside.state(), CubeState::Sampling);
    EXPECT_EQ(aside.nextBackoff(), CubePolicy::kFirstBackoff);
}

TEST(CachePolicy, EmptiedCubeWarmsUpAgain) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame(policyFrame(1000, 1000, 3));
    p.afterFrame(policyFrame(1000, 1000, 3));
    p.restart();
    EXPECT_FALSE(p.afterFrame(policyFrame(1000, 0, 3)).judged);
    EXPECT_FALSE(p.bypassed());
}

TEST(CachePolicy, ACctCubeSamplesFirstAndCachesFullyOnlyWhenTheSamplePays) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts, true);
    EXPECT_EQ(p.state(), CubeState::Sampling);
    EXPECT_FALSE(p.afterFrame(policyFrame(100, 0, 3)).judged);  // fills the sample
    EXPECT_TRUE(p.sampling());
    EXPECT_TRUE(p.afterFrame(policyFrame(100, 100, 3)).judged);  // the sample pays
    EXPECT_EQ(p.state(), CubeState::Caching);
    // The first full frame fills the other texels: an investment, not judged.
    EXPECT_FALSE(p.afterFrame(policyFrame(1600, 100, 3)).judged);
    EXPECT_EQ(p.state(), CubeState::Caching);
    EXPECT_TRUE(p.afterFrame(policyFrame(1600, 1600, 3)).judged);
    EXPECT_EQ(p.state(), CubeState::Caching);
    EXPECT_EQ(p.framesSampling(), 2u);
    EXPECT_EQ(p.framesCaching(), 2u);
}

// A sample that pays only a little cannot repay the first full frame (every
// ray looked up, the misses of the unsampled texels stored): full caching
// would lose along the way, so the cube stands aside. One that pays well
// turns full caching on.
TEST(CachePolicy, ASampleMustRepayTheFillOfFullCachingWithinTheFirstBackoff) {
    const CachePolicyCosts costs{0.5, 1.0, 0.0};
    // 100 lookups, all hits of 1-ray trees: 100 saved, 50 spent, 50 gained;
    // the fill would cost 100 x (0.5 + 15/16 x 1.0) = 143.75, repaid in 2.9
    // frames, within 8.
    CubePolicy pays(CachePolicyMode::Auto, costs, true);
    pays.afterFrame(policyFrame(100, 0, 1));
    EXPECT_TRUE(pays.afterFrame(policyFrame(100, 100, 1)).judged);
    EXPECT_EQ(pays.state(), CubeState::Caching);
    // 100 lookups, 52 hits of trees of 1 ray and 48 misses of trees of 1 ray:
    // 52 saved, 50 + 48 stores = 98 spent: a loss already.
    CubePolicy loses(CachePolicyMode::Auto, costs, true);
    loses.afterFrame(policyFrame(100, 0, 1));
    loses.afterFrame(policyFrame(100, 52, 1));
    EXPECT_TRUE(loses.bypassed());
    // 100 lookups, all hits, no stores, hits valued at 0.6 rays: 60 saved, 50
    // spent, 10 gained; 8 frames of it (80) do not repay the fill (143.75).
    CubePolicy marginal(CachePolicyMode::Auto, costs, true);
    marginal.afterFrame(policyFrame(100, 0, 1));
    CubeFrameCounts small = policyFrame(100, 100, 1);
    small.recordedHits = 10;
    small.recordedHitRays = 6;  // a recorded hit spares 0.6 rays
    const auto j = marginal.afterFrame(small);
    EXPECT_TRUE(j.judged);
    EXPECT_GT(j.saving, j.cost);
    EXPECT_TRUE(marginal.bypassed());
    // A cube that caches in full is judged on the frame alone: the fill is
    // behind it. Hits valued at 0.75 rays: 75 saved against 50 spent clears
    // the margin (72), where a sample's 75 would not repay the fill (97.9).
    CubeFrameCounts same = policyFrame(100, 100, 1);
    same.recordedHits = 4;
    same.recordedHitRays = 3;  // a recorded hit spares 0.75 rays
    CubePolicy full(CachePolicyMode::Auto, costs, false);
    full.afterFrame(policyFrame(100, 0, 1));
    full.afterFrame(same);
    EXPECT_EQ(full.state(), CubeState::Caching);
    CubePolicy sampled(CachePolicyMode::Auto, costs, true);
    sampled.afterFrame(policyFrame(100, 0, 1));
    sampled.afterFrame(same);
    EXPECT_TRUE(sampled.bypassed());
}

// In an animated scene the region tests of a cube's blocks count against it,
// and a cube whose dependencies are tracked pays more per lookup and store.
TEST(CachePolicy, TrackedCubesPayForLookupsStoresAndRegionTests) {
    const CachePolicyCosts costs{0.5, 1.0, 0.0, 0.25, 2.0, 0.5};
    const CachePolicyCosts tracked = costs.tracked();
    EXPECT_DOUBLE_EQ(tracked.lookup, 0.75);
    EXPECT_DOUBLE_EQ(tracked.store, 3.0);
    EXPECT_DOUBLE_EQ(tracked.regionTest, 0.5);
    CubePolicy p(CachePolicyMode::Auto, tracked);
    p.afterFrame(policyFrame(100, 0, 1));
    CubeFrameCounts counts = policyFrame(100, 90, 4);  // 360 saved
    counts.regionTests = 200;
    const auto j = p.afterFrame(counts);
    EXPECT_DOUBLE_EQ(j.saving, 90 * 4.0);
    EXPECT_DOUBLE_EQ(j.cost, 100 * 0.75 + 10 * 3.0 + 200 * 0.5);
    EXPECT_FALSE(p.bypassed());
    counts.regionTests = 600;  // 75 + 30 + 300 > 360
    EXPECT_GT(p.afterFrame(counts).cost, 360.0);
    EXPECT_TRUE(p.bypassed());
}

TEST(CachePolicy, ALosingSampleStandsAsideAndProbesOnTheSampleOverTwoFrames) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts, true);
    p.afterFrame(policyFrame(100, 0, 3));
    EXPECT_TRUE(p.afterFrame(policyFrame(100, 2, 3)).judged);  // 6 saved, 19.8 spent
    EXPECT_TRUE(p.bypassed());
    for (int f = 0; f < CubePolicy::kFirstBackoff; ++f) {
        ASSERT_TRUE(p.bypassed());
        p.afterFrame({});
    }
    // The probe: one frame refreshes the sample, the next is judged.
    ASSERT_TRUE(p.sampling());
    EXPECT_FALSE(p.afterFrame(policyFrame(100, 0, 3)).judged);
    ASSERT_TRUE(p.sampling());
    EXPECT_TRUE(p.afterFrame(policyFrame(100, 1, 3)).judged);
    EXPECT_TRUE(p.bypassed());
    EXPECT_EQ(p.nextBackoff(), 4 * CubePolicy::kFirstBackoff);
    EXPECT_EQ(p.framesSampling(), 4u);
    EXPECT_EQ(p.framesCaching(), 0u);
}

TEST(CachePolicy, OnlyAutoSamples) {
    EXPECT_EQ(CubePolicy(CachePolicyMode::Always, kPolicyTestCosts, true).state(), CubeState::Caching);
    EXPECT_EQ(CubePolicy(CachePolicyMode::Auto, kPolicyTestCosts, false).state(), CubeState::Caching);
    CubePolicy always(CachePolicyMode::Always, kPolicyTestCosts, true);
    for (int f = 0; f < 4; ++f) always.afterFrame(policyFrame(100, 0, 3));
    EXPECT_EQ(always.state(), CubeState::Caching);
    EXPECT_STREQ(cubeStateName(CubeState::Sampling), "sampling");
}

TEST(CachePolicy, TheSampleIsASixteenthOfEveryPartOfTheCube) {
    // A 256² cube: each quarter of each face (128x128 texels, 256 runs of 64)
    // holds sampled runs, and each face close to 1 in 16 of its texels, so
    // the sample sees every part of the cube. Runs are whole: a run's texels
    // are all in or all out.
    constexpr int kSize = 256, kQuarter = 128;
    for (int face = 0; face < 6; ++face) {
        int faceCount = 0;
        for (int qy = 0; qy < 2; ++qy)
            for (int qx = 0; qx < 2; ++qx) {
                int inQuarter = 0;
                for (int y = qy * kQuarter; y < (qy + 1) * kQuarter; ++y)
                    for (int x = qx * kQuarter; x < (qx + 1) * kQuarter; ++x) {
                        const int t = (face * kSize + y) * kSize + x;
                        inQuarter += CubePolicy::sampledTexel(t) ? 1 : 0;
                        ASSERT_EQ(CubePolicy::sampledTexel(t), CubePolicy::sampledTexel(t & ~63)) << t;
                    }
                // 1024 expected of 16384 (16 runs of 256), give or take 3 sd.
                EXPECT_GE(inQuarter, 4 * 64) << "face " << face << " quarter " << qx << "," << qy;
                EXPECT_LE(inQuarter, 28 * 64) << "face " << face << " quarter " << qx << "," << qy;
                faceCount += inQuarter;
            }
        EXPECT_NEAR(static_cast<double>(faceCount) / (kSize * kSize), 1.0 / 16.0, 0.012) << "face " << face;
    }
}

// A cube standing aside traces its rays as without a cache: with costs no hit
// repays, every frame but the warm-up, the judged second frame and the probe
// (bypassedFrame) is bypassed by every cube and is the uncached render bit
// for bit.
TEST(CachePolicyRender, BypassedFramesAreTheUncachedRender) {
    constexpr int kFrames = 6 + CubePolicy::kFirstBackoff;
    const PathRender cached = renderPath("grid-8", CacheTechnique::Cct, kFrames, false, 64, 2, 64, nullptr,
                                         TileBalance::Dynamic, 1, 0, false, VisibleFill::Off, {},
                                         CachePolicyMode::Auto, losingCosts());
    const PathRender plain = renderPath("grid-8", CacheTechnique::None, kFrames, false, 64);
    ASSERT_EQ(cached.stats.size(), static_cast<std::size_t>(kFrames));
    for (int f = 0; f < kFrames; ++f) {
        const FrameCacheStats& c = *cached.stats[static_cast<std::size_t>(f)].cache;
        const bool aside = bypassedFrame(f);
        EXPECT_EQ(c.bypassedCubes(), aside ? static_cast<int>(c.objects.size()) : 0) << "frame " << f;
        // With every cube aside the frame runs the kernel without a cache.
        EXPECT_EQ(c.tracedAsUncached, aside) << "frame " << f;
        if (!aside) continue;
        EXPECT_EQ(c.lookups(), 0u);
        EXPECT_EQ(c.stores(), 0u);
        EXPECT_EQ(c.bypassedRays(), 0u);
        EXPECT_EQ(cached.stats[static_cast<std::size_t>(f)].rays.reflection,
                  plain.stats[static_cast<std::size_t>(f)].rays.reflection);
        EXPECT_TRUE(identicalImages(cached.frames[static_cast<std::size_t>(f)], plain.frames[static_cast<std::size_t>(f)]))
            << "frame " << f;
    }
    // The probe looks the cubes up again, on their samples.
    EXPECT_GT(cached.stats[2 + CubePolicy::kFirstBackoff].cache->lookups(), 0u);
    for (int f = 0; f < kFrames; ++f)
        EXPECT_EQ(cached.stats[static_cast<std::size_t>(f)].cache->samplingCubes(),
                  samplingFrame(f) ? static_cast<int>(cached.stats[static_cast<std::size_t>(f)].cache->objects.size()) : 0)
            << "frame " << f;
}

// A sampling cube looks up and stores only the rays of its sampled texels: a
// sixteenth of them, give or take; the other rays are traced. Still camera,
// calibrated costs: every sampled lookup of the second frame hits (the first
// stored exactly those texels), the sample pays, and the third frame caches
// fully. The first frame, all misses, is the uncached render bit for bit.
TEST(CachePolicyRender, SampledFramesLookUpTheSampleOnlyAndItPredictsFullCaching) {
    constexpr int kFrames = 4;
    const PathRender cached = renderPath("grid-8", CacheTechnique::Cct, kFrames, true, 96, 2, 64, nullptr,
                                         TileBalance::Dynamic, 1, 0, false, VisibleFill::Off, {},
                                         CachePolicyMode::Auto);
    const PathRender plain = renderPath("grid-8", CacheTechnique::None, 1, true, 96);
    const auto cacheOf = [&](int f) -> const FrameCacheStats& { return *cached.stats[static_cast<std::size_t>(f)].cache; };
    for (int f = 0; f < 2; ++f) {
        const FrameCacheStats& c = cacheOf(f);
        EXPECT_EQ(c.samplingCubes(), static_cast<int>(c.objects.size())) << "frame " << f;
        const double sampled = static_cast<double>(c.lookups()) / static_cast<double>(c.lookups() + c.bypassedRays());
        EXPECT_GT(sampled, 1.0 / 32.0) << "frame " << f;
        EXPECT_LT(sampled, 1.0 / 8.0) << "frame " << f;
    }
    EXPECT_EQ(cacheOf(0).hits(), 0u);
    EXPECT_TRUE(identicalImages(cached.frames[0], plain.frames[0]));
    EXPECT_GT(cacheOf(1).lookups(), 0u);
    EXPECT_EQ(cacheOf(1).hits(), cacheOf(1).lookups());
    for (int f = 2; f < kFrames; ++f) {
        EXPECT_EQ(cacheOf(f).samplingCubes(), 0) << "frame " << f;
        EXPECT_EQ(cacheOf(f).bypassedCubes(), 0) << "frame " << f;
        EXPECT_EQ(cacheOf(f).bypassedRays(), 0u) << "frame " << f;
    }
    // The second frame's hits (on sampled texels) recorded their trees (1 to
    // 255 rays): every later hit is valued at their mean.
    for (int f = 1; f < kFrames; ++f) {
        const ObjectCacheStats& o = cacheOf(f).objects[0];
        EXPECT_GE(o.policySaving, static_cast<double>(o.hits)) << "frame " << f;
        EXPECT_LE(o.policySaving, 255.0 * static_cast<double>(o.hits)) << "frame " << f;
    }
    // Full caching: the fill frame looks up every ray, the next hits all it
    // looks up (fewer: the hits' trees are not traced, so their later bounces
    // do not ask).
    EXPECT_LT(cacheOf(2).hits(), cacheOf(2).lookups());
    EXPECT_EQ(cacheOf(3).hits(), cacheOf(3).lookups());
}

// Stores of a sampling cube land in its sample only.
TEST(CachePolicyRender, ASamplingCubeStoresOnlySampledTexels) {
    const PathRender cached = renderPath("grid-8", CacheTechnique::Cct, 1, true, 96, 2, 64, nullptr,
                                         TileBalance::Dynamic, 1, 0, false, VisibleFill::Off, {},
                                         CachePolicyMode::Auto);
    std::size_t stored = 0;
    for (const auto& words : cached.texels)
        for (std::size_t t = 0; t < words.size(); ++t) {
            if (words[t] == CachingCube::kInvalidTexel) continue;
            ++stored;
            EXPECT_TRUE(CubePolicy::sampledTexel(static_cast<int>(t))) << "texel " << t;
        }
    EXPECT_GT(stored, 0u);
}

TEST(CachePolicyRender, AlwaysIsTheDefaultBehaviour) {
    // The library's default is `always`; asking for it changes nothing.
    const PathRender byDefault = renderPath("grid-8", CacheTechnique::Cct, 4, false, 64, 2, 64);
    const PathRender always = renderPath("grid-8", CacheTechnique::Cct, 4, false, 64, 2, 64, nullptr,
                                         TileBalance::Dynamic, 1, 0, false, VisibleFill::Off, {},
                                         CachePolicyMode::Always, losingCosts());
    for (std::size_t f = 0; f < 4; ++f) {
        EXPECT_TRUE(identicalImages(byDefault.frames[f], always.frames[f])) << "frame " << f;
        EXPECT_EQ(always.stats[f].cache->bypassedCubes(), 0);
    }
    EXPECT_EQ(byDefault.texels, always.texels);
}

TEST(CachePolicyRender, AutoIsTheSameOnOneAndTwoThreads) {
    // The calibrated costs, along grid-32's orbit, whatever they decide.
    const auto run = [](int threads) {
        return renderPath("grid-32", CacheTechnique::Cct, 10, false, 64, threads, 64, nullptr, TileBalance::Dynamic, 1,
                          0, false, VisibleFill::Off, {}, CachePolicyMode::Auto);
    };
    const PathRender one = run(1), two = run(2);
    for (std::size_t f = 0; f < one.frames.size(); ++f) {
        EXPECT_TRUE(identicalImages(one.frames[f], two.frames[f])) << "frame " << f;
        for (std::size_t o = 0; o < one.stats[f].cache->objects.size(); ++o) {
            EXPECT_EQ(one.stats[f].cache->objects[o].state, two.stats[f].cache->objects[o].state);
            EXPECT_EQ(one.stats[f].cache->objects[o].policyCost, two.stats[f].cache->objects[o].policyCost);
        }
    }
    EXPECT_EQ(one.texels, two.texels);
}

// Animated: while every cube stands aside the frames are the uncached ones,
// and the cubes, emptied when they stepped aside, cost no region tests; the
// sampling frames' texels are tested against every change.
TEST(CachePolicyRender, AnimatedSceneBypassedFramesAreTheUncachedRender) {
    const auto scene = makeBuiltinScene("room-moving");
    ASSERT_TRUE(scene.has_value());
    const RenderSettings settings = losingAnimatedSettings();
    RenderSettings plainSettings = settings;
    plainSettings.cache.techniqueOverride = CacheTechnique::None;
    RenderSession cached(*scene, settings), plain(*scene, plainSettings);
    constexpr int kFrames = 8;
    for (int f = 0; f < kFrames; ++f) {
        const float t = static_cast<float>(f) / 30.0f;
        cached.setTime(t);
        plain.setTime(t);
        Image a, b;
        const FrameStats sa = cached.render(scene->camera, a);
        plain.render(scene->camera, b);
        const bool aside = bypassedFrame(f);
        ASSERT_TRUE(sa.cache.has_value());
        EXPECT_EQ(sa.cache->bypassedCubes() > 0, aside) << "frame " << f;
        if (aside) {
            EXPECT_TRUE(identicalImages(a, b)) << "frame " << f;
            // Stepping aside emptied the cube: no change tests its blocks.
            for (const ObjectCacheStats& o : sa.cache->objects) EXPECT_EQ(o.regionTests, 0u) << "frame " << f;
        } else if (f > 0) {
            // The sample's texels are tested against every change.
            std::uint64_t tests = 0;
            for (const ObjectCacheStats& o : sa.cache->objects) tests += o.regionTests;
            EXPECT_GT(tests, 0u) << "frame " << f;
        }
    }
}

// In an animated scene a cube that steps aside empties itself, and the
// frame that follows, every cube aside, is rendered as uncached.
TEST(CachePolicyRender, AnimatedSceneCubeEmptiesItselfWhenItStepsAside) {
    const auto scene = makeBuiltinScene("orbit");
    ASSERT_TRUE(scene.has_value());
    RenderSession cached(*scene, losingAnimatedSettings());
    for (int f = 0; f < 3; ++f) {
        cached.setTime(static_cast<float>(f) / 30.0f);
        Image a;
        const FrameStats stats = cached.render(scene->camera, a);
        ASSERT_TRUE(stats.cache.has_value());
        EXPECT_EQ(stats.cache->tracedAsUncached, f == 2) << "frame " << f;
    }
    const RayCache& cache = cached.cache();
    ASSERT_FALSE(cache.empty());
    for (const SceneObject& object : scene->objects) {
        const int id = static_cast<int>(&object - scene->objects.data());
        if (cache.cachesObject(id)) {
            EXPECT_EQ(cache.cube(id).validCount(), 0u) << object.name;
        }
    }
}
