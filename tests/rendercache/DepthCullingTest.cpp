// Depth culling's rule (rendercache/DepthCulling.h): a reprojected sample is
// hidden when at least three of its 3x3 neighbours are nearer by the
// threshold share of its depth and they outnumber the other occupied
// neighbours.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "rendercache/DepthCulling.h"
#include "rendercache/PixelState.h"

using namespace raycache;

namespace {

// The rule over a whole image, as the classification pass applies it
// (rendercache/PixelClassificationPass.cpp): each Reprojected pixel decided
// from the depths alone, then the decisions written, so none sees another's
// result. Returns how many were culled.
std::int64_t cullOccludedSamples(const PointImage& image, float threshold, std::vector<PixelState>& state) {
    const auto stride = static_cast<std::size_t>(image.stride());
    std::vector<std::size_t> hidden;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const auto i = static_cast<std::size_t>(y * image.width() + x);
            const std::uint32_t* row = image.keyData() + image.pixelIndex(x, y);
            if (state[i] == PixelState::Reprojected && hiddenByNearerKeys(row - stride, row, row + stride, threshold))
                hidden.push_back(i);
        }
    for (std::size_t i : hidden) state[i] = PixelState::Culled;
    return static_cast<std::int64_t>(hidden.size());
}

// A 3x3 image (margin 1) whose centre sample is at depth 10; `pattern` gives
// the 8 neighbours row by row, skipping the centre: 'n' nearer (depth 5),
// 'f' not nearer (depth 10), 'b' barely nearer (9.5: within the threshold),
// '.' empty.
bool centreCulled(const std::string& pattern, PixelState centre = PixelState::Reprojected, float threshold = 0.1f) {
    PointImage image;
    image.reset(3, 3, 1);
    std::vector<PixelState> state(9, PixelState::Hole);
    std::size_t k = 0;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) {
            if (x == 1 && y == 1) {
                image.place(1, 1, 10.0f);
                state[4] = centre;
                continue;
            }
            const char c = pattern[k++];
            if (c == '.') continue;
            image.place(x, y, c == 'n' ? 5.0f : c == 'b' ? 9.5f : 10.0f);
            state[static_cast<std::size_t>(y * 3 + x)] = PixelState::Reprojected;
        }
    std::vector<PixelState> before = state;
    const std::int64_t culled = cullOccludedSamples(image, threshold, state);
    // Only the centre can change: every neighbour here is not farther than it.
    for (std::size_t i = 0; i < 9; ++i) {
        if (i == 4) continue;
        EXPECT_EQ(state[i], before[i]) << pattern << " pixel " << i;
    }
    EXPECT_EQ(culled, state[4] == PixelState::Culled ? 1 : 0);
    return state[4] == PixelState::Culled;
}

}  // namespace

TEST(DepthCulling, AFarSampleWithMostlyNearerNeighboursIsCulled) {
    EXPECT_TRUE(
        centreCulled("nnn"
                     "nn"
                     "fff"));  // 5 nearer, 3 not
    EXPECT_FALSE(
        centreCulled("nnn"
                     "nf"
                     "fff"));  // 4 nearer, 4 not: a tie keeps it
}

TEST(DepthCulling, TheRuleCaseByCase) {
    // Straight silhouette: a row of nearer samples above, the rest not nearer: kept.
    EXPECT_FALSE(
        centreCulled("nnn"
                     "ff"
                     "fff"));
    // Inside a nearer surface with gaps: culled.
    EXPECT_TRUE(
        centreCulled("nnn"
                     "nf"
                     "nff"));  // 5 nearer, 3 not
    EXPECT_TRUE(
        centreCulled("nnn"
                     "nn"
                     "nnn"));  // all nearer
    EXPECT_TRUE(
        centreCulled("nnn"
                     ".."
                     "..."));  // 3 nearer, 0 other occupied
    EXPECT_TRUE(
        centreCulled("n.n"
                     ".f"
                     "n.n"));  // 4 nearer, 1 not
    EXPECT_FALSE(
        centreCulled("n.n"
                     ".."
                     "..."));  // only 2 nearer: never culled
    EXPECT_FALSE(
        centreCulled("nnn"
                     "ff"
                     "f.."));  // 3 nearer, 3 not: not outnumbered
    EXPECT_TRUE(
        centreCulled("nnn"
                     "ff"
                     "..."));  // 3 nearer, 2 not
    // Nearer by less than the threshold (9.5 > 10 * 0.9) counts as not nearer.
    EXPECT_FALSE(
        centreCulled("bbb"
                     "bb"
                     "bbb"));
    EXPECT_TRUE(
        centreCulled("bbb"
                     "bb"
                     "bbb",
                     PixelState::Reprojected, 0.04f));
    // Fresh samples are never culled (traced this frame: they are what the camera sees).
    EXPECT_FALSE(
        centreCulled("nnn"
                     "nn"
                     "nnn",
                     PixelState::Fresh));
}

TEST(DepthCulling, NeighboursInTheMarginCountAndDecisionsReadDepthsNotEarlierDecisions) {
    // A 4x1 strip: samples at depths 10, 20, 40 left to right at x = 0..2, x = 3 empty;
    // above and below (the margin) samples at depth 1.
    PointImage image;
    image.reset(4, 1, 1);
    std::vector<PixelState> state(4, PixelState::Reprojected);
    state[3] = PixelState::Hole;
    for (int x = -1; x <= 4; ++x) {
        image.place(x, -1, 1.0f);
        image.place(x, 1, 1.0f);
    }
    image.place(0, 0, 10.0f);
    image.place(1, 0, 20.0f);
    image.place(2, 0, 40.0f);
    const std::int64_t culled = cullOccludedSamples(image, 0.1f, state);
    // Each has 6 nearer margin neighbours: all three culled, whichever is decided first.
    EXPECT_EQ(culled, 3);
    for (int x = 0; x < 3; ++x) EXPECT_EQ(state[static_cast<std::size_t>(x)], PixelState::Culled) << x;
    EXPECT_EQ(state[3], PixelState::Hole);
}

// The row kernel decides as the per-pixel rule, lane by lane and in its
// scalar tail: widths that are not a multiple of any register's lanes, keys
// empty, equal, at the threshold's edge and random.
TEST(DepthCulling, TheRowKernelDecidesAsThePerPixelRule) {
    std::uint64_t state = 12345;
    const auto next = [&state] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<std::uint32_t>(state >> 33);
    };
    const float depths[] = {1.0f, 5.0f, 9.0f, 9.5f, 10.0f, 10.0f, 11.0f, 0.25f};
    int hiddenSeen = 0;
    for (const float threshold : {0.1f, 0.5f, 0.0f})
        for (int width = 1; width <= 40; ++width)
            for (int trial = 0; trial < 8; ++trial) {
                const int stride = width + 2;
                std::vector<std::uint32_t> keys(static_cast<std::size_t>(3 * stride));
                for (std::uint32_t& key : keys) {
                    const std::uint32_t r = next() % 10;
                    key = r >= 8 ? PointImage::emptyKey()
                                 : PointImage::key(depths[r] +
                                                   (trial == 7 ? 0.0f : 0.001f * static_cast<float>(next() % 3)));
                }
                const std::uint32_t* row = keys.data() + stride + 1;
                std::vector<unsigned char> hidden(static_cast<std::size_t>(width), 7);
                hiddenByNearerKeysRow(row - stride, row, row + stride, width, threshold, hidden.data());
                for (int x = 0; x < width; ++x) {
                    const bool expected = hiddenByNearerKeys(row - stride + x, row + x, row + stride + x, threshold);
                    ASSERT_EQ(hidden[static_cast<std::size_t>(x)], expected ? 1 : 0)
                        << "width " << width << ", x " << x << ", threshold " << threshold;
                    hiddenSeen += expected ? 1 : 0;
                }
            }
    EXPECT_GT(hiddenSeen, 100);  // the rule held often enough to be tested both ways
}
