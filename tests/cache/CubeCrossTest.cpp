// The unfolded cross of a caching cube: every face in its cell of the
// thesis' Figure 3.3, texels unflipped, invalid texels black, empty cells grey.
#include "cache/CubeCross.h"

#include <gtest/gtest.h>

#include <array>

using namespace raycache;

namespace {

constexpr int kSize = 4;

// Distinct per face and per texel, and exactly representable in RGB9E5
// (multiples of 1/8 below 1), so the decoded color equals it.
Rgb texelColor(int face, int x, int y) {
    return {0.125f * static_cast<float>(face + 1), 0.125f * static_cast<float>(x + 1),
            0.125f * static_cast<float>(y + 1)};
}

// Texels on a face's diagonal stay invalid.
bool leftInvalid(int x, int y) { return x == y; }

// Writes texelColor into every off-diagonal texel, addressing each one the
// way a renderer does: by a direction through its centre.
CachingCube filledCube() {
    CachingCube cube({0, 0, 0}, kSize);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                if (leftInvalid(x, y)) continue;
                const Vec3 d = cubeTexelCenterDirection({static_cast<CubeFace>(f), x, y}, kSize);
                EXPECT_TRUE(cube.writeIfInvalid(cube.texelIndexFor(d), CachingCube::encodeTexel(texelColor(f, x, y))));
            }
    return cube;
}

struct Cell {
    CubeFace face;
    int column, row;
};

// Figure 3.3: +Y above +Z; -X, +Z, +X, -Z in the middle row; -Y below +Z.
constexpr std::array<Cell, 6> kCells{{{CubeFace::PosY, 1, 0},
                                      {CubeFace::NegX, 0, 1},
                                      {CubeFace::PosZ, 1, 1},
                                      {CubeFace::PosX, 2, 1},
                                      {CubeFace::NegZ, 3, 1},
                                      {CubeFace::NegY, 1, 2}}};

}  // namespace

TEST(CubeCross, EveryFaceLandsUnflippedInItsCell) {
    const CachingCube cube = filledCube();
    ASSERT_EQ(cube.validCount(), 6u * (kSize * kSize - kSize));
    const Image cross = unfoldCubeCross(cube);
    ASSERT_EQ(cross.width(), 4 * kSize);
    ASSERT_EQ(cross.height(), 3 * kSize);
    for (const Cell& cell : kCells) {
        const int f = static_cast<int>(cell.face);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const Rgb expected = leftInvalid(x, y) ? Rgb{0.0f} : texelColor(f, x, y);
                EXPECT_EQ(cross.at(cell.column * kSize + x, cell.row * kSize + y), expected)
                    << "face " << f << " texel (" << x << ", " << y << ")";
            }
    }
}

TEST(CubeCross, EmptyCellsAreDarkGreyAndAnEmptyCubeIsBlack) {
    const Image cross = unfoldCubeCross(CachingCube({1, 2, 3}, kSize));
    std::array<std::array<bool, 4>, 3> isFace{};
    for (const Cell& cell : kCells)
        isFace[static_cast<std::size_t>(cell.row)][static_cast<std::size_t>(cell.column)] = true;
    for (int y = 0; y < cross.height(); ++y)
        for (int x = 0; x < cross.width(); ++x) {
            const bool face = isFace[static_cast<std::size_t>(y / kSize)][static_cast<std::size_t>(x / kSize)];
            EXPECT_EQ(cross.at(x, y), face ? Rgb{0.0f} : Rgb{0.1f}) << "pixel (" << x << ", " << y << ")";
        }
}

namespace {

// Where the first pixel of `color` is in `image`, or (-1, -1).
std::array<int, 2> pixelOf(const Image& image, const Rgb& color) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (image.at(x, y) == color) return {x, y};
    return {-1, -1};
}

}  // namespace

TEST(CubeCross, NeighbouringDirectionsAcrossASeamAreNeighbouringPixels) {
    // Two directions a hair either side of a cube edge must show side by side
    // in the cross: the unfolding keeps the seams inside the cross continuous.
    struct Seam {
        Vec3 first, second;
        int dx, dy;  // where the second lands relative to the first
    };
    const Seam seams[] = {
        {{0.999f, 0.1f, 1.0f}, {1.0f, 0.1f, 0.999f}, 1, 0},    // +Z | +X
        {{1.0f, 0.1f, -0.999f}, {0.999f, 0.1f, -1.0f}, 1, 0},  // +X | -Z
        {{-1.0f, 0.1f, 0.999f}, {-0.999f, 0.1f, 1.0f}, 1, 0},  // -X | +Z
        {{0.1f, 1.0f, 0.999f}, {0.1f, 0.999f, 1.0f}, 0, 1},    // +Y over +Z
        {{0.1f, -0.999f, 1.0f}, {0.1f, -1.0f, 0.999f}, 0, 1},  // +Z over -Y
    };
    const Rgb a{1.0f, 0.0f, 0.0f}, b{0.0f, 1.0f, 0.0f};
    for (const Seam& seam : seams) {
        CachingCube cube({0, 0, 0}, kSize);
        cube.writeIfInvalid(cube.texelIndexFor(seam.first), CachingCube::encodeTexel(a));
        cube.writeIfInvalid(cube.texelIndexFor(seam.second), CachingCube::encodeTexel(b));
        const Image cross = unfoldCubeCross(cube);
        const auto pa = pixelOf(cross, a), pb = pixelOf(cross, b);
        ASSERT_GE(pa[0], 0);
        ASSERT_GE(pb[0], 0);
        EXPECT_EQ(pb[0] - pa[0], seam.dx) << "seam " << (&seam - seams);
        EXPECT_EQ(pb[1] - pa[1], seam.dy) << "seam " << (&seam - seams);
    }
}
