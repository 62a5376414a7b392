// reconstructionBytes(), the counted model of what reconstruction moves:
// on a frame small enough to count by hand, every pass is the records it
// touches times their sizes; the model is linear in the counts (one more
// sample adds exactly its records); and the statistics' GB/s is 0, not NaN
// or infinity, when no time was measured.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/Rgb.h"
#include "render/CameraRays.h"
#include "render/RenderCacheStats.h"
#include "rendercache/PixelState.h"
#include "rendercache/ReconstructionBytes.h"
#include "rendercache/Reprojection.h"
#include "rendercache/SamplePool.h"

using namespace raycache;

namespace {

// The record sizes, from the types themselves.
constexpr std::int64_t kPoint = sizeof(SamplePoint), kLook = sizeof(SampleLook), kReshade = sizeof(ReshadeInputs),
                       kTexturing = sizeof(SampleTexturing);
constexpr std::int64_t kKey = sizeof(std::uint32_t), kSlot = sizeof(std::uint32_t), kNext = sizeof(std::int32_t);
constexpr std::int64_t kLanded = sizeof(ReprojectionScratch::Landed), kState = sizeof(PixelState);
constexpr std::int64_t kFloat = sizeof(float), kInt = sizeof(int), kByte = 1, kRequest = sizeof(PixelCoord),
                       kFilm = sizeof(Rgb), kSource = sizeof(std::int32_t);

// A 2x2 image with a 1-pixel margin (16 pixel slots) and one overflow slot
// in use: 5 samples, 4 of them land; 3 win their pixel in the first round,
// the fourth loses, takes a neighbour by the second chance; one lands far
// from its band. Of the winners one depends on the eye and two are
// textured. One pixel of the image is a hole (3 show a sample, one of them
// textured and re-fetched); it is filled by the 3x3 from 3 neighbours, and
// re-fetched from a textured surface. The request map (one 8x8 tile) asks
// for 1 pixel; the predicted one for 1, a hole, kept.
ReconstructionCounts tinyFrame() {
    ReconstructionCounts c;
    c.width = 2;
    c.height = 2;
    c.pixelSlots = 16;
    c.usedSlots = 17;
    c.liveSamples = 5;
    c.offered = 4;
    c.farOffers = 1;
    c.secondChances = 1;
    c.predicts = true;
    c.placed = 4;
    c.moved = 1;
    c.reshadeCopied = 1;
    c.texturingCopied = 2;
    c.holes = 1;
    c.culls = true;
    c.retextured = 1;
    c.tiles = 1;
    c.requestMap = true;
    c.requested = 1;
    c.pixelsInRequestedTiles = 4;
    c.predictionMap = true;
    c.predictedOffered = 1;
    c.predictedKept = 1;
    c.pixelsInPredictedTiles = 4;
    c.filled3x3 = 1;
    c.rowsWithHoles = 1;
    c.filledRefetch = true;
    c.retexturedHoles = 1;
    return c;
}

}  // namespace

TEST(ReconstructionBytes, ATinyFrameCountsEveryPassFromItsRecords) {
    const ReconstructionBytes b = reconstructionBytes(tinyFrame());

    // First round: 16 keys cleared; 17 points and 5 looks read; 17 next
    // pixels written; 4 keys read by the offers; 3 first-round winners and
    // the 1 second-chance winner write a key and a slot; the far sample and
    // the loser are listed and read back; the loser reads 8 keys.
    EXPECT_EQ(b.firstRound, 16 * kKey + 17 * kPoint + 5 * kLook + 17 * kNext + 4 * kKey + 3 * (kKey + kSlot) +
                                1 * 2 * kLanded + 1 * 2 * kLanded + 1 * 8 * kKey + 1 * (kKey + kSlot));
    // Copy: 16 keys read; 12 empty slots marked; 4 winners: slot read, point
    // and look read and written; 1 mark cleared; 1 reshading and 2 texturing
    // records read and written; 16 next pixels written, 4 read.
    EXPECT_EQ(b.copy, 16 * kKey + 12 * kPoint + 4 * (kSlot + 2 * kPoint + 2 * kLook) + 1 * kKey + 1 * 2 * kReshade +
                          2 * 2 * kTexturing + 16 * kNext + 4 * kNext);
    // Holes: 4 keys, 4 culling flags written and read, 4 states and
    // priorities, 3 looks, 1 re-fetch (point, parts, look).
    EXPECT_EQ(b.holes,
              4 * kKey + 4 * 2 * kByte + 4 * (kState + kFloat) + 3 * kLook + 1 * (kPoint + kTexturing + kLook));
    // Request maps: each reads 4 priorities for the sums and 4 again for the
    // one tile with rays, writes and reads the tile's sum and count, writes 1
    // request. The prediction also clears, reads and writes 4 coverage
    // flags and 4 priorities, reads 16 next pixels, and erases from its list
    // of 1 (request and flag read, the kept one written).
    const std::int64_t oneMap = 4 * kFloat + 1 * 2 * (kFloat + kInt) + 4 * kFloat + 1 * kRequest;
    EXPECT_EQ(b.requestMaps,
              oneMap + 4 * kByte + 16 * kNext + 4 * (kByte + kFloat) + oneMap + 1 * (kRequest + kByte) + 1 * kRequest);
    // Fills: 4 outcomes cleared, 4 states read as bits; every pixel's look
    // read and its film written; the row with holes' 2 states, keys and
    // points read for the filters; the 3x3 hole's source and outcome; a row
    // of 2 states rewritten; the re-fetch's hole's source and its look, the
    // textured surface's point and parts and the film.
    EXPECT_EQ(b.fills, 4 * kByte + 4 * kState + 4 * (kLook + kFilm) + 1 * 2 * (kState + kKey + kPoint) +
                           1 * (kSource + kByte) + 1 * 2 * (2 * kState + kByte) + 1 * (kSource + kLook) +
                           1 * (kPoint + kTexturing + kFilm));
    EXPECT_EQ(b.total(), b.firstRound + b.copy + b.holes + b.requestMaps + b.fills);
}

TEST(ReconstructionBytes, NothingTouchedIsNoBytes) {
    const ReconstructionBytes b = reconstructionBytes(ReconstructionCounts{});
    EXPECT_EQ(b.total(), 0);
}

TEST(ReconstructionBytes, OneMoreWinningSampleAddsExactlyItsRecords) {
    const ReconstructionCounts base = tinyFrame();
    const ReconstructionBytes before = reconstructionBytes(base);
    // Doubling the live samples alone: each one's look is read, nothing else.
    ReconstructionCounts doubled = base;
    doubled.liveSamples *= 2;
    const ReconstructionBytes d = reconstructionBytes(doubled);
    EXPECT_EQ(d.firstRound - before.firstRound, base.liveSamples * kLook);
    EXPECT_EQ(d.copy, before.copy);
    EXPECT_EQ(d.total() - before.total(), base.liveSamples * kLook);
    // A live sample that lands and wins an empty pixel slot in the first round.
    ReconstructionCounts more = base;
    ++more.liveSamples;
    ++more.offered;
    ++more.placed;
    const ReconstructionBytes m = reconstructionBytes(more);
    EXPECT_EQ(m.firstRound - before.firstRound, kLook + kKey + (kKey + kSlot));
    // Its slot is no longer marked empty; its point and look move, and where
    // it lands through the next camera is read.
    EXPECT_EQ(m.copy - before.copy, -kPoint + kSlot + 2 * kPoint + 2 * kLook + kNext);
    EXPECT_EQ(m.holes, before.holes);
    EXPECT_EQ(m.fills, before.fills);
}

TEST(ReconstructionBytes, DoublingEveryCountDoublesEveryPass) {
    const ReconstructionCounts c = tinyFrame();
    ReconstructionCounts twice = c;
    twice.width *= 2;  // twice the pixels
    for (std::int64_t* n : {&twice.pixelSlots,
                            &twice.usedSlots,
                            &twice.liveSamples,
                            &twice.offered,
                            &twice.farOffers,
                            &twice.secondChances,
                            &twice.placed,
                            &twice.moved,
                            &twice.reshadeCopied,
                            &twice.texturingCopied,
                            &twice.holes,
                            &twice.retextured,
                            &twice.tiles,
                            &twice.requested,
                            &twice.pixelsInRequestedTiles,
                            &twice.predictedOffered,
                            &twice.predictedKept,
                            &twice.pixelsInPredictedTiles,
                            &twice.filled3x3,
                            &twice.filled7x7,
                            &twice.unfilled,
                            &twice.retexturedHoles})
        *n *= 2;
    const ReconstructionBytes a = reconstructionBytes(c), b = reconstructionBytes(twice);
    EXPECT_EQ(b.firstRound, 2 * a.firstRound);
    EXPECT_EQ(b.copy, 2 * a.copy);
    EXPECT_EQ(b.holes, 2 * a.holes);
    EXPECT_EQ(b.requestMaps, 2 * a.requestMaps);
    EXPECT_EQ(b.fills, 2 * a.fills);  // rows with holes the same, each twice as wide
}

TEST(ReconstructionBytes, StatisticsGiveGigabytesPerSecondAndZeroWithoutTime) {
    RenderCacheStats s;
    s.firstRoundBytes = 1'000'000'000;
    s.copyBytes = 500'000'000;
    s.holesBytes = 250'000'000;
    s.requestMapBytes = 250'000'000;
    s.fillBytes = 1'000'000'000;
    EXPECT_EQ(s.reprojectBytes(), 1'500'000'000);
    EXPECT_EQ(s.mapsBytes(), 500'000'000);
    EXPECT_EQ(s.filterBytes(), 1'000'000'000);
    EXPECT_EQ(s.reconstructionBytes(), 3'000'000'000);
    // No time measured: 0, not infinity or NaN.
    EXPECT_EQ(s.reconstructionGbPerSecond(), 0.0);
    EXPECT_EQ(s.reprojectGbPerSecond(), 0.0);
    EXPECT_EQ(s.mapsGbPerSecond(), 0.0);
    EXPECT_EQ(s.filterGbPerSecond(), 0.0);
    s.mapsMs = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(s.mapsGbPerSecond(), 0.0);
    s.reprojectMs = 1000.0;
    s.mapsMs = 250.0;
    s.filterMs = 250.0;
    EXPECT_DOUBLE_EQ(s.reprojectGbPerSecond(), 1.5);
    EXPECT_DOUBLE_EQ(s.mapsGbPerSecond(), 2.0);
    EXPECT_DOUBLE_EQ(s.filterGbPerSecond(), 4.0);
    EXPECT_DOUBLE_EQ(s.reconstructionGbPerSecond(), 2.0);  // 3 GB in 1.5 s
}
