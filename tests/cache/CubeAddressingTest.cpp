// CPU-only properties of cube addressing. Whether the texel is the one OpenGL
// picks is CubeAddressingGlTest.cpp's job; this file pins the table, the
// layout and the invariants the cache relies on.
#include "cache/CubeAddressing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace raycache {
namespace {

TEST(CubeAddressing, EveryTexelCentreMapsBackToItsTexel) {
    for (const int size : {1, 2, 16, 100, 512}) {
        int wrong = 0;
        for (int f = 0; f < 6; ++f) {
            for (int y = 0; y < size; ++y) {
                for (int x = 0; x < size; ++x) {
                    const CubeTexel texel{static_cast<CubeFace>(f), x, y};
                    const CubeTexel back = cubeTexelFromDirection(cubeTexelCenterDirection(texel, size), size);
                    if (back != texel && ++wrong <= 5) {
                        ADD_FAILURE() << "size " << size << " face " << f << " (" << x << ", " << y << ") -> face "
                                      << static_cast<int>(back.face) << " (" << back.x << ", " << back.y << ")";
                    }
                }
            }
        }
        EXPECT_EQ(wrong, 0) << "size " << size;
    }
}

// GL 4.6 core, table 8.19: the major axis picks the face, then
// s = (sc / |ma| + 1) / 2 and t = (tc / |ma| + 1) / 2. The components are
// dyadic so every step is exact and the expected values are too.
TEST(CubeAddressing, FollowsTheSpecTableOnEveryFace) {
    struct Case {
        Vec3 d;
        CubeFace face;
        float sc, tc;
    };
    const Case cases[] = {
        {{1.0f, 0.5f, -0.25f}, CubeFace::PosX, 0.25f, -0.5f},    // sc = -rz, tc = -ry
        {{-2.0f, 0.5f, -0.25f}, CubeFace::NegX, -0.25f, -0.5f},  // sc = +rz, tc = -ry
        {{0.5f, 4.0f, -0.25f}, CubeFace::PosY, 0.5f, -0.25f},    // sc = +rx, tc = +rz
        {{0.5f, -1.0f, -0.25f}, CubeFace::NegY, 0.5f, 0.25f},    // sc = +rx, tc = -rz
        {{0.5f, 0.25f, 1.0f}, CubeFace::PosZ, 0.5f, -0.25f},     // sc = +rx, tc = -ry
        {{0.5f, 0.25f, -0.5f}, CubeFace::NegZ, -0.5f, -0.25f},   // sc = -rx, tc = -ry
    };
    for (const Case& c : cases) {
        const float ma = std::fmax(std::fabs(c.d.x), std::fmax(std::fabs(c.d.y), std::fabs(c.d.z)));
        const CubeCoord coord = cubeCoordFromDirection(c.d);
        EXPECT_EQ(coord.face, c.face) << c.d.x << " " << c.d.y << " " << c.d.z;
        EXPECT_EQ(coord.s, 0.5f * (c.sc / ma + 1.0f)) << c.d.x << " " << c.d.y << " " << c.d.z;
        EXPECT_EQ(coord.t, 0.5f * (c.tc / ma + 1.0f)) << c.d.x << " " << c.d.y << " " << c.d.z;
    }
    // The worked example: +x, s = 0.5 * (0.25 / 1 + 1), t = 0.5 * (-0.5 + 1).
    const CubeCoord example = cubeCoordFromDirection({1.0f, 0.5f, -0.25f});
    EXPECT_EQ(example.s, 0.625f);
    EXPECT_EQ(example.t, 0.25f);
    // And its texel on an 8 x 8 face: (floor(0.625 * 8), floor(0.25 * 8)).
    EXPECT_EQ(cubeTexelFromDirection({1.0f, 0.5f, -0.25f}, 8), (CubeTexel{CubeFace::PosX, 5, 2}));
}

// Which face wins when |components| tie, and what signed zeros do: the table
// leaves it open, llvmpipe (and so raycache) prefers z over y over x and takes
// the sign bit of the major component.
TEST(CubeAddressing, TiesAndSignedZerosFollowLlvmpipe) {
    EXPECT_EQ(cubeCoordFromDirection({1.0f, 1.0f, 1.0f}).face, CubeFace::PosZ);
    EXPECT_EQ(cubeCoordFromDirection({-1.0f, 1.0f, -1.0f}).face, CubeFace::NegZ);
    EXPECT_EQ(cubeCoordFromDirection({1.0f, -1.0f, 0.5f}).face, CubeFace::NegY);
    EXPECT_EQ(cubeCoordFromDirection({-1.0f, 0.5f, 1.0f}).face, CubeFace::PosZ);
    EXPECT_EQ(cubeCoordFromDirection({-0.0f, 1.0f, 0.5f}).face, CubeFace::PosY);
    EXPECT_EQ(cubeCoordFromDirection({-1.0f, -0.0f, 0.0f}).face, CubeFace::NegX);
    // No direction at all still addresses a texel, as in GL: the centre of +z or -z.
    EXPECT_EQ(cubeTexelFromDirection({0.0f, 0.0f, 0.0f}, 4), (CubeTexel{CubeFace::PosZ, 2, 2}));
    EXPECT_EQ(cubeTexelFromDirection({0.0f, 0.0f, -0.0f}, 4), (CubeTexel{CubeFace::NegZ, 2, 2}));
}

TEST(CubeAddressing, EdgesClampToTheFace) {
    // |z| one ulp below |x| = 3: the rounded arithmetic gives s = 1 exactly,
    // which would be column `size`; clamp-to-edge keeps the last column.
    const Vec3 d{3.0f, 0.0f, -0x1.7ffffep+1f};
    EXPECT_EQ(cubeCoordFromDirection(d).s, 1.0f);
    EXPECT_EQ(cubeTexelFromDirection(d, 4), (CubeTexel{CubeFace::PosX, 3, 2}));
    // An exact tie on a cube edge belongs to the z face, where it is column 0.
    EXPECT_EQ(cubeTexelFromDirection({1.0f, 0.25f, -1.0f}, 4), (CubeTexel{CubeFace::NegZ, 0, 1}));
}

TEST(CubeAddressing, IndexIsFaceMajorThenRowThenColumn) {
    for (const int size : {1, 3, 16}) {
        int expected = 0;
        for (int f = 0; f < 6; ++f) {
            for (int y = 0; y < size; ++y) {
                for (int x = 0; x < size; ++x) {
                    EXPECT_EQ(cubeTexelIndex({static_cast<CubeFace>(f), x, y}, size), expected++);
                }
            }
        }
        EXPECT_EQ(expected, 6 * size * size);
    }
    EXPECT_EQ(cubeTexelIndex({CubeFace::NegY, 4, 2}, 10), (3 * 10 + 2) * 10 + 4);
}

std::vector<Vec3> randomDirections(int count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    std::vector<Vec3> out;
    while (static_cast<int>(out.size()) < count) {
        const Vec3 v{gauss(rng), gauss(rng), gauss(rng)};
        if (dot(v, v) > 1e-6f) out.push_back(normalize(v));
    }
    return out;
}

// Scaling by a power of two is exact, so the texel cannot change at all.
TEST(CubeAddressing, PowerOfTwoScalingNeverChangesTheTexel) {
    for (const int size : {1, 16, 100, 512}) {
        for (const Vec3& d : randomDirections(20000, 7u + static_cast<std::uint32_t>(size))) {
            const CubeTexel t = cubeTexelFromDirection(d, size);
            for (const float scale : {0x1p-100f, 0x1p-20f, 0.5f, 2.0f, 0x1p20f, 0x1p100f}) {
                ASSERT_EQ(cubeTexelFromDirection(d * scale, size), t)
                    << "size " << size << " direction (" << d.x << ", " << d.y << ", " << d.z << ") * " << scale;
            }
        }
    }
}

// Any other positive factor rounds the scaled components, which can move a
// direction that sits within rounding error of a texel edge; everywhere else
// the texel must stay.
TEST(CubeAddressing, PositiveScalingKeepsTheTexelAwayFromEdges) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> logScale(-30.0f, 30.0f);
    for (const int size : {1, 16, 100, 512}) {
        const float n = static_cast<float>(size);
        int checked = 0;
        for (const Vec3& d : randomDirections(20000, 11u + static_cast<std::uint32_t>(size))) {
            const CubeCoord c = cubeCoordFromDirection(d);
            const auto nearEdge = [&](float u) {
                const float f = u * n - std::floor(u * n);
                return f < 1e-3f || f > 1.0f - 1e-3f;
            };
            const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
            const float major = std::fmax(ax, std::fmax(ay, az));
            const float second = ax + ay + az - major - std::fmin(ax, std::fmin(ay, az));
            if (nearEdge(c.s) || nearEdge(c.t) || major - second < 1e-3f * major) continue;
            ++checked;
            const CubeTexel t = cubeTexelFromDirection(d, size);
            for (int i = 0; i < 4; ++i) {
                const float scale = std::pow(10.0f, logScale(rng));
                ASSERT_EQ(cubeTexelFromDirection(d * scale, size), t)
                    << "size " << size << " direction (" << d.x << ", " << d.y << ", " << d.z << ") * " << scale;
            }
        }
        EXPECT_GT(checked, 15000) << "size " << size;
    }
}

}  // namespace
}  // namespace raycache
