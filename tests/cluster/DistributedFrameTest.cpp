// The cluster mode's logic without MPI: simulated processes
// (ThreadProcessGroup) render a path together, and process 0's images and
// EVERY process's caches must equal a single-process render bit for bit.
#include <gtest/gtest.h>

#include <array>
#include <mutex>
#include <numeric>

#include "ThreadProcessGroup.h"
#include "cache/PathRender.h"
#include "core/Errors.h"
#include "core/ProcessAgreement.h"
#include "render/FrameRenderer.h"
#include "render/TileAssignment.h"
#include "scene/BuiltinScenes.h"
#include "session/FrameParallelLoop.h"

namespace raycache {
namespace {

constexpr int kFrames = 3;
constexpr int kSize = 48;
constexpr int kCacheResolution = 32;

void expectSameAsOneProcess(const std::string& scene, CacheTechnique technique, int processes, TileBalance balance,
                            std::int64_t prefillPerFrame = 0, int threadsPerProcess = 1) {
    const PathRender one =
        renderPath(scene, technique, kFrames, false, kSize, 2, kCacheResolution, nullptr, balance, 1, prefillPerFrame);
    std::vector<PathRender> runs(static_cast<std::size_t>(processes));
    runAsProcesses(processes, [&](const ProcessGroup& group) {
        runs[static_cast<std::size_t>(group.rank())] = renderPath(scene, technique, kFrames, false, kSize, threadsPerProcess,
                                                                  kCacheResolution, &group, balance, 1, prefillPerFrame);
    });
    const PathRender& root = runs[0];
    ASSERT_EQ(root.frames.size(), one.frames.size());
    for (std::size_t f = 0; f < one.frames.size(); ++f)
        EXPECT_EQ(root.frames[f].pixels(), one.frames[f].pixels()) << scene << " frame " << f;
    for (int r = 0; r < processes; ++r)
        EXPECT_EQ(runs[static_cast<std::size_t>(r)].texels, one.texels) << scene << ": process " << r << "'s caches";
    // Cache statistics are the job's on every process; ray counts on process 0.
    for (std::size_t f = 0; f < one.stats.size(); ++f) {
        EXPECT_EQ(root.stats[f].rays.total(), one.stats[f].rays.total()) << "frame " << f;
        ASSERT_EQ(root.stats[f].cache.has_value(), one.stats[f].cache.has_value());
        if (!one.stats[f].cache) continue;
        for (const PathRender& run : runs) {
            EXPECT_EQ(run.stats[f].cache->lookups(), one.stats[f].cache->lookups());
            EXPECT_EQ(run.stats[f].cache->hits(), one.stats[f].cache->hits());
            EXPECT_EQ(run.stats[f].cache->stores(), one.stats[f].cache->stores());
            EXPECT_EQ(run.stats[f].cache->cdctSteps(), one.stats[f].cache->cdctSteps());
        }
        ASSERT_TRUE(root.stats[f].cluster.has_value());
        // Every tile rendered once, by some process.
        const std::vector<int>& dealt = root.stats[f].cluster->tilesPerProcess;
        EXPECT_EQ(dealt.size(), static_cast<std::size_t>(processes));
        EXPECT_EQ(std::accumulate(dealt.begin(), dealt.end(), 0), tileCount(kSize, kSize, 16)) << "frame " << f;
        if (technique == CacheTechnique::Cct) {
            EXPECT_GT(root.stats[f].cluster->storeBytes, 0u);
        }
    }
}

TEST(DistributedFrame, UncachedEqualsOneProcess) {
    expectSameAsOneProcess("room", CacheTechnique::None, 2, TileBalance::Dynamic);
    expectSameAsOneProcess("room", CacheTechnique::None, 3, TileBalance::Claim);
}

TEST(DistributedFrame, CctCachesIdenticalOnEveryProcess) {
    for (const int processes : {2, 3}) {
        expectSameAsOneProcess("room", CacheTechnique::Cct, processes, TileBalance::Dynamic);
        expectSameAsOneProcess("glass", CacheTechnique::Cct, processes, TileBalance::Static);
        expectSameAsOneProcess("room", CacheTechnique::Cct, processes, TileBalance::Claim);
    }
}

TEST(DistributedFrame, CdctCachesIdenticalOnEveryProcess) {
    expectSameAsOneProcess("glass", CacheTechnique::Cdct, 3, TileBalance::Dynamic);
    expectSameAsOneProcess("room", CacheTechnique::CdctParity, 2, TileBalance::Dynamic);
    expectSameAsOneProcess("glass", CacheTechnique::Cdct, 2, TileBalance::Claim);
}

// Several workers per process claim tiles each and pack their own pixels.
TEST(DistributedFrame, ClaimedTilesWithSeveralThreadsPerProcess) {
    expectSameAsOneProcess("glass", CacheTechnique::Cct, 2, TileBalance::Claim, 0, 2);
}

// The claim counter is reset after every frame, so a second path rendered
// by the same processes (a new renderer) claims its tiles from 0 again.
TEST(DistributedFrame, ClaimCounterStartsAfreshForTheNextRenderer) {
    const PathRender room = renderPath("room", CacheTechnique::Cct, 2, false, kSize, 2, kCacheResolution);
    const PathRender glass = renderPath("glass", CacheTechnique::Cct, 2, false, kSize, 2, kCacheResolution);
    std::vector<PathRender> rooms(2), glasses(2);
    runAsProcesses(2, [&](const ProcessGroup& group) {
        const auto r = static_cast<std::size_t>(group.rank());
        rooms[r] = renderPath("room", CacheTechnique::Cct, 2, false, kSize, 1, kCacheResolution, &group,
                              TileBalance::Claim);
        glasses[r] = renderPath("glass", CacheTechnique::Cct, 2, false, kSize, 1, kCacheResolution, &group,
                                TileBalance::Claim);
    });
    for (std::size_t f = 0; f < 2; ++f) {
        EXPECT_EQ(rooms[0].frames[f].pixels(), room.frames[f].pixels()) << "room frame " << f;
        EXPECT_EQ(glasses[0].frames[f].pixels(), glass.frames[f].pixels()) << "glass frame " << f;
    }
    EXPECT_EQ(glasses[1].texels, glass.texels);
}

// The pre-fill spread over frames: each frame's rows are shared among the
// processes, so the cubes fill alike everywhere. 32² faces are 192 rows of
// 32 texels; 40 rows a frame leave room's mirror cube part-filled for the
// first frames, and its last piece shorter.
TEST(DistributedFrame, SpreadCdctPrefillIdenticalOnEveryProcess) {
    expectSameAsOneProcess("room", CacheTechnique::Cdct, 3, TileBalance::Dynamic, 40 * kCacheResolution);
}

TEST(DistributedFrame, WholeFramesEqualOneProcess) {
    const auto scene = makeBuiltinScene("room");
    ASSERT_TRUE(scene);
    RenderSettings settings;
    settings.width = settings.height = kSize;
    settings.threads = 1;
    settings.cache.techniqueOverride = CacheTechnique::None;
    ASSERT_TRUE(framesAreIndependent(*scene, settings));
    constexpr int kPathFrames = 5;
    std::vector<Image> one;
    renderFrames(*scene, scene->cameraPath, settings, kPathFrames,
                 [&](const FrameResult&, const Image& film, const RayCache&) { one.push_back(film); });
    std::vector<Image> many;
    std::vector<int> order;
    runAsProcesses(3, [&](const ProcessGroup& group) {
        renderFramesAcrossProcesses(
            *scene, scene->cameraPath, settings, kPathFrames, group,
            [&](const FrameResult& r, const Image& film, const RayCache&) {
                many.push_back(film);  // process 0 only
                order.push_back(r.frame);
            },
            [](int) { return true; }, {}, FrameTimeline{0.0f, scene->fps});
    });
    EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4}));
    ASSERT_EQ(many.size(), one.size());
    for (std::size_t f = 0; f < one.size(); ++f) EXPECT_EQ(many[f].pixels(), one[f].pixels()) << "frame " << f;

    settings.cache.techniqueOverride = CacheTechnique::Cct;
    EXPECT_FALSE(framesAreIndependent(*scene, settings)) << "cached frames depend on the earlier ones";
}

TEST(ProcessAgreement, AFailureOnOneProcessStopsEveryProcess) {
    std::mutex mutex;
    std::vector<std::string> messages;
    std::vector<int> codes;
    runAsProcesses(3, [&](const ProcessGroup& group) {
        try {
            runOnEveryProcess(group, [&] {
                if (group.rank() == 2) throw InputError("scene.json: scene file not found");
            });
        } catch (const ProcessGroupFailure& e) {
            const std::lock_guard lock(mutex);
            messages.push_back(e.what());
            codes.push_back(e.exitCode());
        }
    });
    ASSERT_EQ(messages.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(messages[i], "process 2 of 3: scene.json: scene file not found");
        EXPECT_EQ(codes[i], 2);
    }
}

TEST(ProcessAgreement, TheSameFailureEverywhereNamesNoProcess) {
    std::mutex mutex;
    std::vector<std::string> messages;
    runAsProcesses(2, [&](const ProcessGroup& group) {
        try {
            runOnEveryProcess(group, [] { throw InputError("--width must be positive"); });
        } catch (const ProcessGroupFailure& e) {
            const std::lock_guard lock(mutex);
            messages.push_back(e.what());
        }
    });
    EXPECT_EQ(messages, (std::vector<std::string>{"--width must be positive", "--width must be positive"}));
}

TEST(ProcessAgreement, OneProcessPassesTheErrorUnchanged) {
    const SingleProcessGroup one;
    EXPECT_THROW(runOnEveryProcess(one, [] { throw InputError("bad"); }), InputError);
    EXPECT_NO_THROW(runOnEveryProcess(one, [] {}));
}

TEST(TileAssignment, InterleavedDealsRoundRobin) {
    EXPECT_EQ(interleavedTileOwners(7, 3), (std::vector<int>{0, 1, 2, 0, 1, 2, 0}));
}

TEST(TileAssignment, BalancedEvensOutUnevenCosts) {
    // One expensive tile and many cheap ones: LPT gives the expensive tile a
    // process of its own and deals the rest to the others.
    std::vector<double> costs(9, 1.0);
    costs[4] = 8.0;
    const std::vector<int> owners = balancedTileOwners(costs, 2);
    std::vector<double> load(2, 0.0);
    for (std::size_t t = 0; t < costs.size(); ++t) load[static_cast<std::size_t>(owners[t])] += costs[t];
    EXPECT_DOUBLE_EQ(std::max(load[0], load[1]), 8.0);
    EXPECT_EQ(owners, balancedTileOwners(costs, 2)) << "deterministic";
    // Interleaving would have given 4 + 8 = 12 to one process.
    EXPECT_EQ(balancedTileOwners(std::vector<double>{}, 3), std::vector<int>{});
}

// The names --tile-balance takes, in the order its message lists them.
TEST(TileAssignment, NamesItsBalances) {
    EXPECT_EQ(kTileBalances, (std::array{TileBalance::Static, TileBalance::Dynamic, TileBalance::Claim}));
    EXPECT_STREQ(tileBalanceName(TileBalance::Static), "static");
    EXPECT_STREQ(tileBalanceName(TileBalance::Dynamic), "dynamic");
    EXPECT_STREQ(tileBalanceName(TileBalance::Claim), "claim");
}

}  // namespace
}  // namespace raycache
