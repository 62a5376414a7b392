// The cache policy (cache/CachePolicy.h): its decision on constructed counts,
// and renders that step cubes aside checked against their ground truth, the
// uncached render.
#include <gtest/gtest.h>

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

bool policyImagesMatch(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.pixels().data(), b.pixels().data(), a.pixels().size() * sizeof(Rgb)) == 0;
}

// Under costs no hit repays: frame 0 fills (not judged), frame 1 loses, frames
// 2-5 stand aside, frame 6 probes and loses, frames 7-14 stand aside.
bool bypassedFrame(int f) { return (f >= 2 && f < 2 + CubePolicy::kFirstBackoff) || f >= 3 + CubePolicy::kFirstBackoff; }

// Costs no hit can repay: every judged frame loses.
CachePolicyCosts losingCosts() { return {1e6, 1e6, 1e6}; }

}  // namespace

TEST(CachePolicy, ParsesItsModes) {
    EXPECT_EQ(parseCachePolicyMode("auto"), CachePolicyMode::Auto);
    EXPECT_EQ(parseCachePolicyMode("always"), CachePolicyMode::Always);
    EXPECT_FALSE(parseCachePolicyMode("sometimes").has_value());
    EXPECT_STREQ(cachePolicyModeName(CachePolicyMode::Auto), "auto");
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

TEST(CachePolicy, BreakEvenKeepsCaching) {
    CubePolicy p(CachePolicyMode::Auto, {1.0, 0.0, 0.0});
    p.afterFrame(policyFrame(10, 0, 1));
    p.afterFrame(policyFrame(10, 10, 1));  // saving 10, cost 10: not a loss
    EXPECT_FALSE(p.bypassed());
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
    p.afterFrame(policyFrame(1000, 0, 3));  // loses: bypass 4
    for (int f = 0; f < CubePolicy::kFirstBackoff; ++f) p.afterFrame({});
    p.afterFrame(policyFrame(1000, 0, 3));  // the probe loses: bypass 8
    EXPECT_EQ(p.nextBackoff(), 16);
    for (int f = 0; f < 8; ++f) p.afterFrame({});
    ASSERT_FALSE(p.bypassed());
    p.afterFrame(policyFrame(1000, 900, 3));  // the probe pays: caching again
    EXPECT_FALSE(p.bypassed());
    EXPECT_EQ(p.nextBackoff(), CubePolicy::kFirstBackoff);
    EXPECT_EQ(p.framesBypassed(), 12u);
    EXPECT_EQ(p.framesCaching(), 4u);
}

TEST(CachePolicy, NoEvidenceOfTreesCountsAHitAsOneRay) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame({100, 100, 0, 0, 0, 0});  // filled from elsewhere: no traced tree yet
    const auto j = p.afterFrame({100, 100, 0, 0, 0, 0});
    EXPECT_DOUBLE_EQ(j.saving, 100.0 * CachePolicyCosts::kMinimumTree);
    EXPECT_FALSE(p.bypassed());
}

TEST(CachePolicy, EmptiedCubeWarmsUpAgain) {
    CubePolicy p(CachePolicyMode::Auto, kPolicyTestCosts);
    p.afterFrame(policyFrame(1000, 1000, 3));
    p.afterFrame(policyFrame(1000, 1000, 3));
    p.restart();
    EXPECT_FALSE(p.afterFrame(policyFrame(1000, 0, 3)).judged);
    EXPECT_FALSE(p.bypassed());
}

// A cube standing aside traces its rays as without a cache: with costs no hit
// repays, every frame but the warm-up, the judged second frame and the probe
// (bypassedFrame) is bypassed by every cube and is the uncached render bit
// for bit.
TEST(CachePolicyRender, BypassedFramesAreTheUncachedRender) {
    constexpr int kFrames = 8;
    const PathRender cached = renderPath("grid-8", CacheTechnique::Cct, kFrames, false, 64, 2, 64, nullptr,
                                         TileBalance::Dynamic, 1, 0, false, VisibleFill::Off, {},
                                         CachePolicyMode::Auto, losingCosts());
    const PathRender plain = renderPath("grid-8", CacheTechnique::None, kFrames, false, 64);
    ASSERT_EQ(cached.stats.size(), static_cast<std::size_t>(kFrames));
    for (int f = 0; f < kFrames; ++f) {
        const FrameCacheStats& c = *cached.stats[static_cast<std::size_t>(f)].cache;
        const bool aside = bypassedFrame(f);
        EXPECT_EQ(c.bypassedCubes(), aside ? static_cast<int>(c.objects.size()) : 0) << "frame " << f;
        if (!aside) continue;
        EXPECT_EQ(c.lookups(), 0u);
        EXPECT_EQ(c.stores(), 0u);
        EXPECT_GT(c.bypassedRays(), 0u);
        EXPECT_EQ(cached.stats[static_cast<std::size_t>(f)].rays.reflection,
                  plain.stats[static_cast<std::size_t>(f)].rays.reflection);
        EXPECT_TRUE(policyImagesMatch(cached.frames[static_cast<std::size_t>(f)], plain.frames[static_cast<std::size_t>(f)]))
            << "frame " << f;
    }
    // The probe looks the cubes up again.
    EXPECT_GT(cached.stats[2 + CubePolicy::kFirstBackoff].cache->lookups(), 0u);
}

TEST(CachePolicyRender, AlwaysIsTheDefaultBehaviour) {
    // The library's default is `always`; asking for it changes nothing.
    const PathRender byDefault = renderPath("grid-8", CacheTechnique::Cct, 4, false, 64, 2, 64);
    const PathRender always = renderPath("grid-8", CacheTechnique::Cct, 4, false, 64, 2, 64, nullptr,
                                         TileBalance::Dynamic, 1, 0, false, VisibleFill::Off, {},
                                         CachePolicyMode::Always, losingCosts());
    for (std::size_t f = 0; f < 4; ++f) {
        EXPECT_TRUE(policyImagesMatch(byDefault.frames[f], always.frames[f])) << "frame " << f;
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
        EXPECT_TRUE(policyImagesMatch(one.frames[f], two.frames[f])) << "frame " << f;
        for (std::size_t o = 0; o < one.stats[f].cache->objects.size(); ++o) {
            EXPECT_EQ(one.stats[f].cache->objects[o].bypassed, two.stats[f].cache->objects[o].bypassed);
            EXPECT_EQ(one.stats[f].cache->objects[o].policyCost, two.stats[f].cache->objects[o].policyCost);
        }
    }
    EXPECT_EQ(one.texels, two.texels);
}

// Animated: while every cube stands aside the frames are the uncached ones
// (the cubes keep invalidating meanwhile, so what a probe reads is what the
// invalidation left valid; the oracle tests cover that).
TEST(CachePolicyRender, AnimatedSceneBypassedFramesAreTheUncachedRender) {
    const auto scene = makeBuiltinScene("room-moving");
    ASSERT_TRUE(scene.has_value());
    RenderSettings settings;
    settings.width = settings.height = 48;
    settings.threads = 2;
    settings.cache.techniqueOverride = CacheTechnique::Cct;
    settings.cache.resolutionOverride = 64;
    RenderSettings plainSettings = settings;
    plainSettings.cache.techniqueOverride = CacheTechnique::None;
    settings.cache.policy = CachePolicyMode::Auto;
    settings.cache.policyCosts = losingCosts();
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
            EXPECT_TRUE(policyImagesMatch(a, b)) << "frame " << f;
        }
    }
}
