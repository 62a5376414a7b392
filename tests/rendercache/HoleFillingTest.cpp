// fillHoles(): the 3x3 weighted mean (edge neighbours 2, corners 1) for
// holes next to a sample, the 7x7 box mean only where the 3x3 finds none,
// and Unfilled beyond; given the samples' surfaces, the mean of one
// surface's samples only (edge-aware). Expected values are computed here in double from the
// samples' known colours.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "rendercache/HoleFilling.h"
#include "rendercache/PointImage.h"
#include "rendercache/SurfaceClusters.h"

using namespace raycache;

namespace {

// A colour no two pixels share, small integers so sums are exact.
Rgb colourOf(int x, int y) {
    return Rgb{static_cast<float>(x), static_cast<float>(y), static_cast<float>(x * y % 7)};
}

struct Synthetic {
    int width, height;
    std::vector<PixelState> state;
    Image film;
    Synthetic(int w, int h)
        : width(w), height(h), state(static_cast<std::size_t>(w * h), PixelState::Reprojected), film(w, h) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) film.at(x, y) = colourOf(x, y);
    }
    PixelState& s(int x, int y) { return state[static_cast<std::size_t>(y * width + x)]; }
    void hole(int x, int y, PixelState kind = PixelState::Hole) {
        s(x, y) = kind;
        film.at(x, y) = Rgb{-1.0f};  // must be overwritten (or, unfilled, left)
    }
};

struct DRgb {
    double r = 0, g = 0, b = 0;
};

void expectColour(const Rgb& got, const DRgb& want, int x, int y) {
    EXPECT_NEAR(got.r, want.r, 1e-5 * (1 + std::abs(want.r))) << x << "," << y;
    EXPECT_NEAR(got.g, want.g, 1e-5 * (1 + std::abs(want.g))) << x << "," << y;
    EXPECT_NEAR(got.b, want.b, 1e-5 * (1 + std::abs(want.b))) << x << "," << y;
}

// The mean of colourOf over the pixels `isSample` accepts among (x, y)'s
// neighbours within `radius`, weighted by `weight(dx, dy)`.
template <class IsSample, class Weight>
DRgb mean(int x, int y, int radius, int width, int height, IsSample isSample, Weight weight) {
    DRgb sum;
    double total = 0;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height || !isSample(nx, ny)) continue;
            const double w = weight(dx, dy);
            const Rgb c = colourOf(nx, ny);
            sum.r += w * c.r;
            sum.g += w * c.g;
            sum.b += w * c.b;
            total += w;
        }
    return {sum.r / total, sum.g / total, sum.b / total};
}

double edgesTwoCornersOne(int dx, int dy) {
    return dx == 0 || dy == 0 ? 2.0 : 1.0;
}
double box(int, int) {
    return 1.0;
}

}  // namespace

TEST(HoleFilling, AOnePixelHoleTakesTheWeightedMeanOfItsEightNeighbours) {
    Synthetic img(7, 5);
    img.hole(3, 2);
    img.s(2, 1) = PixelState::Fresh;  // fresh samples count as samples too
    const FillCounts c = fillHoles(img.state, img.film, Parallel(1));
    EXPECT_EQ(c.filled3x3, 1);
    EXPECT_EQ(c.filled7x7, 0);
    EXPECT_EQ(c.unfilled, 0);
    EXPECT_EQ(c.rowsWithHoles, 1);
    EXPECT_EQ(img.s(3, 2), PixelState::Filled3x3);
    // (2*(3,1) + 2*(2,2) + 2*(4,2) + 2*(3,3) + (2,1) + (4,1) + (2,3) + (4,3)) / 12, by hand for r and g:
    // r = (2*3 + 2*2 + 2*4 + 2*3 + 2 + 4 + 2 + 4) / 12 = 3, g = (2*1 + 2*2 + 2*2 + 2*3 + 1 + 1 + 3 + 3) / 12 = 2.
    EXPECT_FLOAT_EQ(img.film.at(3, 2).r, 3.0f);
    EXPECT_FLOAT_EQ(img.film.at(3, 2).g, 2.0f);
    // b = x * y % 7: edges 3, 4, 1, 2, corners 2, 4, 6, 5: 37 / 12.
    EXPECT_FLOAT_EQ(img.film.at(3, 2).b, 37.0f / 12.0f);
    expectColour(img.film.at(3, 2),
                 mean(
                     3, 2, 1, 7, 5, [](int x, int y) { return !(x == 3 && y == 2); }, edgesTwoCornersOne),
                 3, 2);
    // Samples are untouched.
    EXPECT_EQ(img.film.at(2, 2), colourOf(2, 2));
}

TEST(HoleFilling, AFiveByFiveHoleFillsItsRingBy3x3AndOnlyItsCentreBy7x7) {
    constexpr int kW = 17, kH = 15;
    Synthetic img(kW, kH);
    const auto inHole = [](int x, int y) { return x >= 5 && x <= 9 && y >= 4 && y <= 8; };
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if (inHole(x, y)) img.hole(x, y, (x + y) % 3 == 0 ? PixelState::Culled : PixelState::Hole);
    const FillCounts c = fillHoles(img.state, img.film, Parallel(2));
    EXPECT_EQ(c.filled3x3, 16);
    EXPECT_EQ(c.filled7x7, 9);
    EXPECT_EQ(c.unfilled, 0);
    EXPECT_EQ(c.rowsWithHoles, 5);
    const auto isSample = [&](int x, int y) { return !inHole(x, y); };
    for (int y = 4; y <= 8; ++y)
        for (int x = 5; x <= 9; ++x) {
            const bool ring = x == 5 || x == 9 || y == 4 || y == 8;
            EXPECT_EQ(img.s(x, y), ring ? PixelState::Filled3x3 : PixelState::Filled7x7) << x << "," << y;
            // Only the samples are averaged, never pixels the first pass filled.
            expectColour(
                img.film.at(x, y),
                ring ? mean(x, y, 1, kW, kH, isSample, edgesTwoCornersOne) : mean(x, y, 3, kW, kH, isSample, box), x,
                y);
        }
    // The centre's 7x7 box holds 49 - 25 samples; by hand: r = mean of x over them = 7.
    EXPECT_FLOAT_EQ(img.film.at(7, 6).r, 7.0f);
    EXPECT_FLOAT_EQ(img.film.at(7, 6).g, 6.0f);
}

TEST(HoleFilling, OnePixelHolesNeverReachThe7x7) {
    constexpr int kW = 12, kH = 9;
    Synthetic img(kW, kH);
    int holes = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if ((x + y) % 2 == 0) {  // a checkerboard: every hole has samples on all edges
                img.hole(x, y);
                ++holes;
            }
    const FillCounts c = fillHoles(img.state, img.film, Parallel(2));
    EXPECT_EQ(c.filled3x3, holes);
    EXPECT_EQ(c.filled7x7, 0);
    EXPECT_EQ(c.unfilled, 0);
    const auto isSample = [](int x, int y) { return (x + y) % 2 != 0; };
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if ((x + y) % 2 == 0) {
                EXPECT_EQ(img.s(x, y), PixelState::Filled3x3);
                expectColour(img.film.at(x, y), mean(x, y, 1, kW, kH, isSample, edgesTwoCornersOne), x, y);
            }
}

TEST(HoleFilling, APixelWithNoSampleWithinThreeStaysUnfilledAndUntouched) {
    constexpr int kW = 9, kH = 9;
    Synthetic img(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            if (!(x == 0 && y == 0)) img.hole(x, y);
    const FillCounts c = fillHoles(img.state, img.film, Parallel(1));
    // (1,0), (0,1), (1,1) by the 3x3; within 3 of (0,0): x, y <= 3, less those 3 and the sample.
    EXPECT_EQ(c.filled3x3, 3);
    EXPECT_EQ(c.filled7x7, 16 - 1 - 3);
    EXPECT_EQ(c.unfilled, 81 - 16);
    EXPECT_EQ(img.s(3, 3), PixelState::Filled7x7);
    EXPECT_EQ(img.film.at(3, 3), colourOf(0, 0));
    EXPECT_EQ(img.s(4, 0), PixelState::Unfilled);
    EXPECT_EQ(img.s(8, 8), PixelState::Unfilled);
    EXPECT_EQ(img.film.at(4, 0), Rgb{-1.0f}) << "left for the caller";
    EXPECT_EQ(img.film.at(8, 8), Rgb{-1.0f});
}

// Rows where the 7x7 holes are many (a wide hole: column sums) and rows
// where they are few and far apart (a box per hole) both give the 7x7 mean,
// on one and two threads.
TEST(HoleFilling, WideAndScatteredHolesBothTakeThe7x7MeanOnAnyThreadCount) {
    constexpr int kW = 48, kH = 20;
    std::vector<std::vector<bool>> hole(kH, std::vector<bool>(kW, false));
    for (int y = 4; y < 11; ++y)
        for (int x = 2; x < 40; ++x) hole[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] = true;  // wide
    for (int cx : {5, 42})  // two 3x3 holes far apart on rows 14-16: one 7x7 pixel each
        for (int y = 14; y < 17; ++y)
            for (int x = cx - 1; x <= cx + 1; ++x) hole[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)] = true;
    const auto isSample = [&](int x, int y) { return !hole[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)]; };
    Image reference;
    for (int threads : {1, 2}) {
        Synthetic img(kW, kH);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                if (!isSample(x, y)) img.hole(x, y);
        const FillCounts c = fillHoles(img.state, img.film, Parallel(threads));
        // The oracle: the nearest sample's distance (in the max norm) decides.
        const auto sampleWithin = [&](int x, int y, int r) {
            for (int ny = std::max(0, y - r); ny <= std::min(kH - 1, y + r); ++ny)
                for (int nx = std::max(0, x - r); nx <= std::min(kW - 1, x + r); ++nx)
                    if (isSample(nx, ny)) return true;
            return false;
        };
        std::int64_t filled7x7 = 0, unfilled = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                if (isSample(x, y) || sampleWithin(x, y, 1)) continue;
                if (!sampleWithin(x, y, 3)) {
                    EXPECT_EQ(img.s(x, y), PixelState::Unfilled) << x << "," << y;
                    ++unfilled;
                    continue;
                }
                ++filled7x7;
                ASSERT_EQ(img.s(x, y), PixelState::Filled7x7) << x << "," << y;
                expectColour(img.film.at(x, y), mean(x, y, 3, kW, kH, isSample, box), x, y);
            }
        EXPECT_EQ(c.filled7x7, filled7x7);
        EXPECT_EQ(c.unfilled, unfilled);
        EXPECT_GT(filled7x7, 100);
        EXPECT_EQ(img.s(5, 15), PixelState::Filled7x7);
        EXPECT_EQ(img.s(42, 15), PixelState::Filled7x7);
        if (threads == 1) reference = img.film;
        else EXPECT_EQ(img.film.pixels(), reference.pixels());
    }
}

// With the samples' colours given from a pool laid out like the Render
// Cache's (a margin around the image), the film is written in the same
// passes and ends as it does when the colours were copied into it first.
TEST(HoleFilling, ColoursReadFromThePoolGiveTheSameFilmAsColoursInTheFilm) {
    constexpr int kW = 40, kH = 18, kMargin = 2, kStride = kW + 2 * kMargin;
    const auto isHole = [](int x, int y) { return (x * 7 + y * 13) % 5 < 2 || (x > 10 && x < 25 && y > 5 && y < 12); };
    for (int threads : {1, 2}) {
        Synthetic copied(kW, kH), fromPool(kW, kH);
        std::vector<SampleLook> looks(static_cast<std::size_t>(kStride * (kH + 2 * kMargin)));
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                looks[static_cast<std::size_t>((y + kMargin) * kStride + x + kMargin)].color = colourOf(x, y);
                fromPool.film.at(x, y) = Rgb{-2.0f};  // nothing in the film yet
                if (isHole(x, y)) {
                    copied.hole(x, y);
                    fromPool.hole(x, y);
                }
            }
        const SampleColors colours{looks.data(), static_cast<std::size_t>(kMargin * kStride + kMargin),
                                   static_cast<std::size_t>(kStride)};
        const FillCounts a = fillHoles(copied.state, copied.film, Parallel(threads));
        const FillCounts b = fillHoles(fromPool.state, fromPool.film, Parallel(threads), nullptr, &colours);
        EXPECT_GT(a.filled3x3, 0);
        EXPECT_GT(a.filled7x7, 0);
        EXPECT_EQ(a.filled3x3, b.filled3x3);
        EXPECT_EQ(a.filled7x7, b.filled7x7);
        EXPECT_EQ(a.unfilled, b.unfilled);
        EXPECT_EQ(copied.state, fromPool.state);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const PixelState s = copied.s(x, y);
                if (s == PixelState::Unfilled) continue;  // left to the caller
                ASSERT_EQ(copied.film.at(x, y), fromPool.film.at(x, y)) << x << "," << y << ", " << threads << " threads";
            }
    }
}

namespace {

// A silhouette: the left of the image shows object 1 at depth 2 in red, the
// right object 2 at depth 9 in blue, with holes along the edge between them
// (for the 3x3 filter) and a hole wide enough for the 7x7 filter across it.
struct Silhouette {
    static constexpr int kW = 24, kH = 16, kEdge = 11;  // columns < kEdge are the near object
    static constexpr Rgb kNear{1.0f, 0.0f, 0.0f}, kFar{0.0f, 0.0f, 1.0f};
    Synthetic img{kW, kH};
    PointImage depths;
    std::vector<SamplePoint> points;
    Silhouette() : points(static_cast<std::size_t>(kW * kH)) {
        depths.reset(kW, kH, 0);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const bool near = x < kEdge;
                img.film.at(x, y) = near ? kNear : kFar;
                depths.place(x, y, near ? 2.0f : 9.0f);
                points[static_cast<std::size_t>(y * kW + x)].objectId = near ? 1 : 2;
                const bool edgeHole = (x == kEdge - 1 || x == kEdge) && (x + y) % 2 == 0;
                const bool wideHole = y >= 6 && y <= 11 && x >= kEdge - 3 && x <= kEdge + 2;
                if (edgeHole || wideHole) {
                    img.hole(x, y);
                    depths.clear(x, y);
                }
            }
    }
    SampleSurfaces surfaces() const { return SampleSurfaces{&depths, points.data(), 0, static_cast<std::size_t>(kW)}; }
};

}  // namespace

// Given the samples' surfaces, a filled hole shows one side of a depth
// discontinuity, never a blend; without them (the same holes) the filters
// blend the two sides, which is what makes this test able to fail.
TEST(HoleFilling, EdgeAwareFillsDoNotMixColoursAcrossADepthDiscontinuity) {
    Silhouette aware, plain;
    const SampleSurfaces surfaces = aware.surfaces();
    const FillCounts a = fillHoles(aware.img.state, aware.img.film, Parallel(2), nullptr, nullptr, &surfaces);
    const FillCounts b = fillHoles(plain.img.state, plain.img.film, Parallel(2));
    EXPECT_GT(a.filled3x3, 10);
    EXPECT_GT(a.filled7x7, 0);
    EXPECT_EQ(a.filled3x3, b.filled3x3);
    EXPECT_EQ(a.filled7x7, b.filled7x7);
    int blendedWithout = 0;
    for (int y = 0; y < Silhouette::kH; ++y)
        for (int x = 0; x < Silhouette::kW; ++x) {
            const Rgb c = aware.img.film.at(x, y);
            EXPECT_TRUE(c == Silhouette::kNear || c == Silhouette::kFar) << x << "," << y << ": " << c.r << " " << c.b;
            const Rgb p = plain.img.film.at(x, y);
            blendedWithout += (p == Silhouette::kNear || p == Silhouette::kFar) ? 0 : 1;
        }
    EXPECT_GT(blendedWithout, 10);
}

// Which side a hole takes: the surface with more weight among its samples;
// of two equally weighted, the farther (a moving camera's holes at a
// silhouette are mostly what it newly sees behind the object).
TEST(HoleFilling, AnEdgeHoleTakesTheHeavierSurfaceAndOnATieTheFarther) {
    Silhouette s;
    const SampleSurfaces surfaces = s.surfaces();
    fillHoles(s.img.state, s.img.film, Parallel(1), nullptr, nullptr, &surfaces);
    for (int y = 0; y < Silhouette::kH; ++y)
        for (int x = Silhouette::kEdge - 1; x <= Silhouette::kEdge; ++x) {
            if (s.img.s(x, y) != PixelState::Filled3x3) continue;
            float nearWeight = 0.0f, farWeight = 0.0f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= Silhouette::kW || ny >= Silhouette::kH) continue;
                    if (!s.depths.hasSample(nx, ny) || (dx == 0 && dy == 0)) continue;
                    // Filled pixels were holes: only the original samples count.
                    const bool wasHole = ((nx == Silhouette::kEdge - 1 || nx == Silhouette::kEdge) && (nx + ny) % 2 == 0) ||
                                         (ny >= 6 && ny <= 11 && nx >= Silhouette::kEdge - 3 && nx <= Silhouette::kEdge + 2);
                    if (wasHole) continue;
                    (nx < Silhouette::kEdge ? nearWeight : farWeight) += (dx == 0 || dy == 0) ? 2.0f : 1.0f;
                }
            const Rgb want = nearWeight > farWeight ? Silhouette::kNear : Silhouette::kFar;
            EXPECT_EQ(s.img.film.at(x, y), want) << x << "," << y << ": near " << nearWeight << ", far " << farWeight;
        }
}

// The 3x3 filter and, where it finds no sample, the 7x7 one against their
// rules written out one neighbour at a time (row by row; edge neighbours 2,
// corners 1 in the 3x3, all 1 in the 7x7; the edge-aware groups of
// SurfaceClusters) on rows wider than a word of PixelStateBits, random
// states, colours, depths and objects and a wide hole across a word's end:
// the same colours bit for bit, the same sources and states, and the
// samples' colours copied from the pool.
namespace {

// The fills against their rules applied one neighbour at a time, on random
// states, colours, objects and depths: `objects` objects at depths in
// [1, maxDepth]. With one object and depths within a tenth of each other
// every hole's samples lie on one surface (the 3x3 filter's lanes decide
// alone); with three objects and a wider range most holes see two or more.
// The image is taller than a band of rows (HoleFilling.cpp) and its width
// no multiple of a register's lanes.
void expectFillsFollowTheirRules(int objects, float maxDepth) {
    constexpr int kW = 150, kH = 41, kMargin = 1, kStride = kW + 2 * kMargin;
    std::mt19937 random(38);
    std::uniform_int_distribution<int> anyState(0, static_cast<int>(PixelState::Hole)), anyObject(0, objects - 1);
    std::uniform_real_distribution<float> anyColour(0.0f, 1.0f), anyDepth(1.0f, maxDepth);
    std::vector<PixelState> states(static_cast<std::size_t>(kW * kH));
    for (PixelState& s : states) s = static_cast<PixelState>(anyState(random));
    for (int y = 2; y < 7; ++y)
        for (int x = 50; x < 80; ++x) states[static_cast<std::size_t>(y * kW + x)] = PixelState::Hole;  // a 7x7's
    std::vector<SampleLook> looks(static_cast<std::size_t>(kStride * (kH + 2 * kMargin)));
    std::vector<SamplePoint> points(looks.size());
    PointImage depths;
    depths.reset(kW, kH, kMargin);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const auto slot = depths.pixelIndex(x, y);
            looks[slot].color = Rgb{anyColour(random), anyColour(random), anyColour(random)};
            points[slot].objectId = anyObject(random);
            depths.place(x, y, anyDepth(random));
        }
    const SampleColors colours{looks.data(), depths.pixelIndex(0, 0), static_cast<std::size_t>(kStride)};
    const SampleSurfaces surfaces{&depths, points.data(), depths.pixelIndex(0, 0), static_cast<std::size_t>(kStride)};
    for (int threads : {1, 2}) {
        std::vector<PixelState> state = states;
        Image film(kW, kH);
        std::vector<std::int32_t> source;
        fillHoles(state, film, Parallel(threads), nullptr, &colours, &surfaces, &source);
        int filled = 0, filled7x7 = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const PixelState before = states[static_cast<std::size_t>(y * kW + x)];
                if (showsSample(before)) {
                    ASSERT_EQ(film.at(x, y), colours.at(x, y)) << x << "," << y;
                    continue;
                }
                const auto box = [&](int radius, bool weighted) {
                    SurfaceClusters groups;
                    for (int dy = -radius; dy <= radius; ++dy)
                        for (int dx = -radius; dx <= radius; ++dx) {
                            const int nx = x + dx, ny = y + dy;
                            if (nx < 0 || ny < 0 || nx >= kW || ny >= kH ||
                                !showsSample(states[static_cast<std::size_t>(ny * kW + nx)]))
                                continue;
                            groups.add(colours.at(nx, ny), weighted && (dx == 0 || dy == 0) ? 2.0f : 1.0f,
                                       surfaces.depth(nx, ny), surfaces.object(nx, ny), ny * kW + nx);
                        }
                    return groups;
                };
                SurfaceClusters groups = box(1, true);
                PixelState want = PixelState::Filled3x3;
                if (groups.empty()) {
                    groups = box(3, false);
                    want = PixelState::Filled7x7;
                    ++filled7x7;
                }
                if (groups.empty()) {
                    ASSERT_EQ(state[static_cast<std::size_t>(y * kW + x)], PixelState::Unfilled) << x << "," << y;
                    continue;
                }
                ++filled;
                ASSERT_EQ(state[static_cast<std::size_t>(y * kW + x)], want) << x << "," << y;
                ASSERT_EQ(film.at(x, y), groups.mean()) << x << "," << y << ", " << threads << " threads";
                ASSERT_EQ(source[static_cast<std::size_t>(y * kW + x)], groups.chosenSource()) << x << "," << y;
            }
        EXPECT_GT(filled, kW);
        EXPECT_GT(filled7x7, 20);
    }
}

}  // namespace

TEST(HoleFilling, TheFillsAreTheirRulesOneNeighbourAtATimeBitForBit) {
    expectFillsFollowTheirRules(3, 1.3f);
}

TEST(HoleFilling, HolesWithinOneSurfaceAreTheirRuleBitForBit) {
    expectFillsFollowTheirRules(1, 1.05f);
}
