#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "CdctFixtures.h"
#include "PathRender.h"
#include "cache/RayCache.h"

namespace raycache {
namespace {

// room: one mirror sphere. 16² faces: 96 rows of 16 texels, 1536 texels.
constexpr int kPrefillImageSize = 40;
constexpr int kResolution = 16;
constexpr int kRows = 6 * kResolution;
constexpr int kCubeTexels = kRows * kResolution;

// Improved CDCT with its pre-fill spread over frames fills the same cube
// as the pre-fill in one frame, bit for bit, once its last row is in; the
// frames before that trace every reflected ray, so they equal the uncached
// render exactly; every frame traces at most its budget of pre-fill rays.
TEST(PrefillSpread, FillsTheSameCubeOverSeveralFramesWithinTheBudget) {
    constexpr int kRowsPerFrame = 10;
    constexpr std::int64_t kBudget = kRowsPerFrame * kResolution;
    constexpr int kFillFrames = (kRows + kRowsPerFrame - 1) / kRowsPerFrame;  // 10
    constexpr int kFrames = kFillFrames + 2;
    const PathRender atOnce = renderPath("room", CacheTechnique::Cdct, kFrames, true, kPrefillImageSize, 2, kResolution);
    const PathRender spread = renderPath("room", CacheTechnique::Cdct, kFrames, true, kPrefillImageSize, 2, kResolution, nullptr,
                                         TileBalance::Dynamic, 1, kBudget);
    const PathRender uncached = renderPath("room", CacheTechnique::None, kFrames, true, kPrefillImageSize, 2, kResolution);
    ASSERT_EQ(spread.frames.size(), static_cast<std::size_t>(kFrames));

    EXPECT_EQ(spread.texels, atOnce.texels);
    std::uint64_t prefilled = 0;
    for (int f = 0; f < kFrames; ++f) {
        const std::uint64_t rays = spread.stats[static_cast<std::size_t>(f)].rays.prefill;
        EXPECT_LE(rays, static_cast<std::uint64_t>(kBudget)) << "frame " << f;
        prefilled += rays;
        // The cube is complete after the pre-fill of frame kFillFrames - 1
        // (counting from 0); up to and including that frame, every lookup
        // misses and the image is the uncached one.
        if (f < kFillFrames) {
            EXPECT_EQ(spread.frames[static_cast<std::size_t>(f)].pixels(),
                      uncached.frames[static_cast<std::size_t>(f)].pixels())
                << "frame " << f;
        }
    }
    EXPECT_EQ(prefilled, static_cast<std::uint64_t>(kCubeTexels));
    // Once filled, the images are the filled cube's, as with the pre-fill at once.
    EXPECT_EQ(spread.frames.back().pixels(), atOnce.frames.back().pixels());
    EXPECT_NE(spread.frames.back().pixels(), uncached.frames.back().pixels());
}

// A budget smaller than one row still makes progress: one row a frame.
TEST(PrefillSpread, BudgetBelowOneRowTracesOneRowAFrame) {
    const PathRender run = renderPath("room", CacheTechnique::Cdct, 4, true, kPrefillImageSize, 1, kResolution, nullptr,
                                      TileBalance::Dynamic, 1, /*prefillPerFrame=*/3);
    for (const FrameStats& s : run.stats) EXPECT_EQ(s.rays.prefill, static_cast<std::uint64_t>(kResolution));
}

// The queue protocol on the cache alone: pieces come in row order within
// the budget, rows out of order are refused, and a cube emptied while its
// rows come in (a scene change, RayCache::clear) starts again from row 0.
TEST(PrefillSpread, PiecesInRowOrderAndARestartAfterTheCubeIsEmptied) {
    RayCacheSettings settings;
    settings.prefillTexelsPerFrame = 10 * kResolution;  // 10 rows a frame
    RayCache cache(cdct_test::oneMirror(CacheTechnique::Cdct, kResolution), settings);
    auto workers = cache.makeWorkers(1);
    const auto frameAsking = [&] {
        cache.beginFrame(workers);
        workers[0].beginBatch(0);
        EXPECT_FALSE(cache.lookup(0, {0, 0, 1.001f}, {0, 0, 1}, workers[0]).has_value());
        return cache.planPrefill(workers);
    };
    const auto rowsOf = [&](int rows) {
        return std::vector<RayCache::PrefillTexel>(static_cast<std::size_t>(rows * kResolution),
                                                   RayCache::PrefillTexel{Rgb{0.5f, 0.5f, 0.5f}, 2.0f});
    };

    std::vector<RayCache::PrefillPiece> plan = frameAsking();
    ASSERT_EQ(plan.size(), 1u);
    EXPECT_EQ(plan[0].firstRow, 0);
    EXPECT_EQ(plan[0].rows, 10);
    EXPECT_THROW(cache.addPrefillRows(0, 5, rowsOf(10)), std::logic_error);  // not the next row
    cache.addPrefillRows(0, 0, rowsOf(10));
    cache.endFrame(workers);

    plan = frameAsking();
    ASSERT_EQ(plan.size(), 1u);
    EXPECT_EQ(plan[0].firstRow, 10);
    cache.endFrame(workers);  // the frame's piece is not handed back: the next frame asks for it again

    cache.clear();  // what a scene change does to the cube
    plan = frameAsking();
    ASSERT_EQ(plan.size(), 1u);
    EXPECT_EQ(plan[0].firstRow, 0) << "rows traced before the change are dropped";
    for (int row = 0; row < kRows; row += 10) {
        const int rows = std::min(10, kRows - row);
        if (row > 0) {
            plan = frameAsking();
            ASSERT_EQ(plan.size(), 1u);
            EXPECT_EQ(plan[0].firstRow, row);
            EXPECT_EQ(plan[0].rows, rows);
        }
        EXPECT_EQ(cache.cube(0).validCount(), 0u) << "no texel before the last row";
        cache.addPrefillRows(0, row, rowsOf(rows));
        cache.endFrame(workers);
    }
    EXPECT_EQ(cache.cube(0).validCount(), cache.cube(0).texelCount());
    cache.beginFrame(workers);
    EXPECT_TRUE(cache.planPrefill(workers).empty());
    cache.endFrame(workers);
}

}  // namespace
}  // namespace raycache
