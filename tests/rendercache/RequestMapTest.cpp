// buildRequestMap(): the budget split over tiles by (1 - alpha) area share +
// alpha priority share, rounded so the counts add up to the budget; inside a
// tile the highest priorities first; all of it a function of the inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "rendercache/RequestMap.h"

using namespace raycache;

namespace {

// 36 x 20 with 8-pixel tiles: 5 x 3 tiles, the last column 4 wide and the
// last row 4 high, so tile areas differ.
constexpr int kW = 36, kH = 20, kTile = 8;

std::vector<float> somePriorities(std::uint64_t salt) {
    std::vector<float> p(kW * kH);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const std::uint64_t h = mixBits(i ^ (salt << 32));
        p[i] = (h % 5 == 0) ? 1.0f : static_cast<float>(h % 17) / 32.0f;  // some holes, ages below 1/2
    }
    return p;
}

int tileArea(const RequestMap& m, int t) {
    const int x0 = (t % m.tilesX) * kTile, y0 = (t / m.tilesX) * kTile;
    return (std::min(kW, x0 + kTile) - x0) * (std::min(kH, y0 + kTile) - y0);
}

int sum(const std::vector<int>& v) {
    int s = 0;
    for (int x : v) s += x;
    return s;
}

// Every requested pixel inside its tile, none twice.
void expectPixelsInTheirTiles(const RequestMap& m) {
    std::set<std::pair<int, int>> seen;
    std::size_t k = 0;
    for (int t = 0; t < m.tilesX * m.tilesY; ++t) {
        const int x0 = (t % m.tilesX) * kTile, y0 = (t / m.tilesX) * kTile;
        for (int r = 0; r < m.tileRequests[static_cast<std::size_t>(t)]; ++r, ++k) {
            const PixelCoord p = m.pixels[k];
            ASSERT_GE(p.x, x0);
            ASSERT_LT(p.x, std::min(kW, x0 + kTile));
            ASSERT_GE(p.y, y0);
            ASSERT_LT(p.y, std::min(kH, y0 + kTile));
            ASSERT_TRUE(seen.insert({p.x, p.y}).second) << p.x << "," << p.y << " twice";
        }
    }
    ASSERT_EQ(k, m.pixels.size());
}

}  // namespace

TEST(RequestMap, TilePrioritiesAreTheSumsOfTheirPixels) {
    const std::vector<float> p = somePriorities(1);
    RequestMap m;
    buildRequestMap(p, kW, kH, kTile, 0.5f, 0, 1, 0, m, Parallel(1));
    ASSERT_EQ(m.tilesX, 5);
    ASSERT_EQ(m.tilesY, 3);
    for (int t = 0; t < 15; ++t) {
        const int x0 = (t % 5) * kTile, y0 = (t / 5) * kTile;
        double q = 0;
        for (int y = y0; y < std::min(kH, y0 + kTile); ++y)
            for (int x = x0; x < std::min(kW, x0 + kTile); ++x) q += p[static_cast<std::size_t>(y * kW + x)];
        EXPECT_FLOAT_EQ(m.tilePriority[static_cast<std::size_t>(t)], static_cast<float>(q));
    }
    EXPECT_TRUE(m.pixels.empty()) << "budget 0: no ray";
    EXPECT_EQ(sum(m.tileRequests), 0);
}

TEST(RequestMap, RequestsAddUpToTheBudgetExactly) {
    for (float alpha : {0.0f, 0.25f, 0.7f, 1.0f})
        for (int budget : {1, 7, 15, 36, 100, 333})
            for (std::uint64_t frame = 0; frame < 40; ++frame) {
                const std::vector<float> p = somePriorities(frame);
                RequestMap m;
                buildRequestMap(p, kW, kH, kTile, alpha, budget, 42, frame, m, Parallel(2));
                ASSERT_EQ(sum(m.tileRequests), budget) << "alpha " << alpha << " frame " << frame;
                ASSERT_EQ(m.pixels.size(), static_cast<std::size_t>(budget));
                expectPixelsInTheirTiles(m);
            }
}

TEST(RequestMap, AlphaZeroGivesEveryTileItsAreaShare) {
    std::vector<float> p(kW * kH, 0.0f);
    p[0] = 1.0f;  // all the priority in one tile: alpha 0 must ignore it
    for (int budget : {15, 50, 200})
        for (std::uint64_t frame = 0; frame < 20; ++frame) {
            RequestMap m;
            buildRequestMap(p, kW, kH, kTile, 0.0f, budget, 3, frame, m, Parallel(1));
            for (int t = 0; t < 15; ++t) {
                const double share = static_cast<double>(budget) * tileArea(m, t) / (kW * kH);
                const int got = m.tileRequests[static_cast<std::size_t>(t)];
                EXPECT_GE(got, std::floor(share)) << "tile " << t << " budget " << budget;
                EXPECT_LE(got, std::ceil(share)) << "tile " << t << " budget " << budget;
            }
        }
}

TEST(RequestMap, AlphaOneSendsNoRayWhereNothingIsWanted) {
    std::vector<float> p(kW * kH, 0.0f);
    // Holes in two tiles only: tile 0 (3 holes) and tile 7 (whole tile).
    p[0] = p[1] = p[static_cast<std::size_t>(kW)] = 1.0f;
    for (int y = 8; y < 16; ++y)
        for (int x = 16; x < 24; ++x) p[static_cast<std::size_t>(y * kW + x)] = 1.0f;
    for (std::uint64_t frame = 0; frame < 20; ++frame) {
        RequestMap m;
        buildRequestMap(p, kW, kH, kTile, 1.0f, 30, 9, frame, m, Parallel(1));
        for (int t = 0; t < 15; ++t) {
            if (t == 0 || t == 7) continue;
            EXPECT_EQ(m.tileRequests[static_cast<std::size_t>(t)], 0) << "tile " << t;
        }
        // Shares 3/67 and 64/67 of 30 rays.
        EXPECT_GE(m.tileRequests[0], 1);
        EXPECT_LE(m.tileRequests[0], 2);
        EXPECT_EQ(m.tileRequests[0] + m.tileRequests[7], 30);
    }
}

TEST(RequestMap, ATileNeverGetsMoreRaysThanPixels) {
    std::vector<float> p(kW * kH, 0.0f);
    p[static_cast<std::size_t>(19 * kW + 35)] = 1.0f;  // the last tile, 4x4 pixels, holds all the priority
    RequestMap m;
    buildRequestMap(p, kW, kH, kTile, 1.0f, 500, 1, 0, m, Parallel(1));
    EXPECT_EQ(m.tileRequests[14], 16);
    for (int t = 0; t < 15; ++t) EXPECT_LE(m.tileRequests[static_cast<std::size_t>(t)], tileArea(m, t));
    expectPixelsInTheirTiles(m);
    // Every pixel's worth of budget with alpha 0: each tile exactly its area.
    buildRequestMap(p, kW, kH, kTile, 0.0f, kW * kH, 1, 0, m, Parallel(1));
    for (int t = 0; t < 15; ++t) EXPECT_EQ(m.tileRequests[static_cast<std::size_t>(t)], tileArea(m, t)) << t;
    expectPixelsInTheirTiles(m);
}

TEST(RequestMap, InsideATileHolesComeBeforeSamplesAndOlderBeforeYounger) {
    std::vector<float> p(kW * kH, 0.0f);
    // Tile 0: 5 holes, 4 old samples (0.4), the rest young (0.1).
    const int holes[][2] = {{0, 0}, {3, 1}, {7, 7}, {2, 5}, {6, 2}};
    const int old[][2] = {{1, 1}, {4, 4}, {5, 0}, {0, 6}};
    for (int y = 0; y < kTile; ++y)
        for (int x = 0; x < kTile; ++x) p[static_cast<std::size_t>(y * kW + x)] = 0.1f;
    for (const auto& h : holes) p[static_cast<std::size_t>(h[1] * kW + h[0])] = 1.0f;
    for (const auto& o : old) p[static_cast<std::size_t>(o[1] * kW + o[0])] = 0.4f;
    for (std::uint64_t frame = 0; frame < 30; ++frame) {
        RequestMap m;
        // alpha 1 and only tile 0 prioritised: all rays go there.
        buildRequestMap(p, kW, kH, kTile, 1.0f, 7, 5, frame, m, Parallel(1));
        ASSERT_EQ(m.tileRequests[0], 7);
        std::set<std::pair<int, int>> got;
        for (const PixelCoord& q : m.pixels) got.insert({q.x, q.y});
        for (const auto& h : holes) EXPECT_TRUE(got.count({h[0], h[1]})) << "hole " << h[0] << "," << h[1];
        int oldTaken = 0;
        for (const auto& o : old) oldTaken += static_cast<int>(got.count({o[0], o[1]}));
        EXPECT_EQ(oldTaken, 2) << "the two rays left go to old samples, not young ones";
        // Fewer rays than holes: holes only.
        buildRequestMap(p, kW, kH, kTile, 1.0f, 3, 5, frame, m, Parallel(1));
        for (const PixelCoord& q : m.pixels) EXPECT_EQ(p[static_cast<std::size_t>(q.y * kW + q.x)], 1.0f);
    }
}

TEST(RequestMap, SameInputsSameRequestsOnAnyThreadCountAndFramesSpreadThem) {
    const std::vector<float> p = somePriorities(77);
    RequestMap a, b;
    buildRequestMap(p, kW, kH, kTile, 0.4f, 60, 11, 5, a, Parallel(1));
    buildRequestMap(p, kW, kH, kTile, 0.4f, 60, 11, 5, b, Parallel(2));
    EXPECT_EQ(a.tileRequests, b.tileRequests);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.tilePriority, b.tilePriority);
    // Uniform priority: only the random tie-break chooses. Over frames the requests move.
    const std::vector<float> flat(kW * kH, 0.25f);
    std::set<std::pair<int, int>> everRequested;
    std::vector<PixelCoord> first;
    int differentFrames = 0;
    for (std::uint64_t frame = 0; frame < 20; ++frame) {
        RequestMap m;
        buildRequestMap(flat, kW, kH, kTile, 0.5f, 36, 11, frame, m, Parallel(1));
        for (const PixelCoord& q : m.pixels) everRequested.insert({q.x, q.y});
        if (frame == 0)
            first = m.pixels;
        else
            differentFrames += m.pixels != first ? 1 : 0;
    }
    EXPECT_EQ(differentFrames, 19);
    EXPECT_GT(everRequested.size(), 36u * 10u) << "20 frames of 36 rays reach far more than 36 pixels";
    // A different seed, a different choice.
    RequestMap s1, s2;
    buildRequestMap(flat, kW, kH, kTile, 0.5f, 36, 1, 3, s1, Parallel(1));
    buildRequestMap(flat, kW, kH, kTile, 0.5f, 36, 2, 3, s2, Parallel(1));
    EXPECT_NE(s1.pixels, s2.pixels);
}

// Inside a tile the priorities are put in steps eight pixels at a time and
// the rest of a row one at a time: an 11-pixel tile uses both, with holes,
// old samples and priorities past either end of [0, 1] (clamped) in each part.
TEST(RequestMap, PrioritiesRankAlikeInEightPixelStepsAndInARowsRest) {
    constexpr int kWidth = 11, kHeight = 3;
    std::vector<float> p(kWidth * kHeight, 0.1f);
    const auto at = [&](int x, int y) -> float& { return p[static_cast<std::size_t>(y * kWidth + x)]; };
    at(3, 1) = -0.5f;
    at(10, 0) = -2.0f;
    const int wanted[][2] = {{2, 0}, {9, 1}, {10, 2}, {5, 2}, {8, 0}};  // holes, then old samples
    at(2, 0) = 1.0f;
    at(9, 1) = 1.0f;
    at(10, 2) = 1.7f;
    at(5, 2) = 0.4f;
    at(8, 0) = 0.4f;
    for (std::uint64_t frame = 0; frame < 30; ++frame) {
        RequestMap m;
        buildRequestMap(p, kWidth, kHeight, kWidth, 1.0f, 5, 7, frame, m, Parallel(1));
        std::set<std::pair<int, int>> got;
        for (const PixelCoord& q : m.pixels) got.insert({q.x, q.y});
        ASSERT_EQ(got.size(), 5u);
        for (const auto& w : wanted) EXPECT_TRUE(got.count({w[0], w[1]})) << w[0] << "," << w[1] << ", frame " << frame;
    }
}
