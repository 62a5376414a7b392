// checkerSquares16() against scene/Texture::sample's checkerboard at
// render/SurfacePoint's texture coordinates, lane by lane: texture
// coordinates from a square's width to past 2^31 and 1e15, negative, on
// square edges, infinite and NaN (the floors' parity without 64-bit
// integers must be floorToInt's).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "rendercache/CheckerLanes.h"

using namespace raycache;

TEST(CheckerLanes, EachLaneIsTextureSamplesSquareBitForBit) {
    const Checkerboard pattern{Rgb{0.9f, 0.8f, 0.2f}, Rgb{0.1f, 0.2f, 0.7f}, 7.0f};
    const Texture texture = Texture::checkerboard(pattern);
    std::mt19937 random(38);
    std::uniform_real_distribution<float> unit(-0.2f, 1.2f), exponent(-3.0f, 17.0f), sign(-1.0f, 1.0f);
    const float special[] = {0.0f, -0.0f, 1.0f / 7.0f, -3.0f / 7.0f, 8388608.0f, 8388609.0f, -8388609.0f,
                             16777215.0f, 2147483520.0f, -2147483520.0f, 2147483648.0f, 3.0e9f, 1.0e15f, -1.0e15f,
                             9.9e14f, 1.0e20f, std::numeric_limits<float>::infinity(),
                             std::numeric_limits<float>::quiet_NaN()};
    const auto coordinate = [&](int i) {
        if (i % 5 == 0) return special[static_cast<std::size_t>(random()) % std::size(special)] / pattern.squaresPerUnit;
        return (sign(random) < 0 ? -1.0f : 1.0f) * std::pow(10.0f, exponent(random)) * unit(random);
    };
    int odd = 0, even = 0;
    for (int block = 0; block < 4000; ++block) {
        CornerTextureCoordinates uv;
        for (auto& corner : uv) corner = {coordinate(block * 6), coordinate(block * 6 + 1)};
        if (block % 3 == 0) uv[1] = uv[0];  // a run of texture coordinates along one corner
        float u[kFloatLanes], v[kFloatLanes];
        for (int k = 0; k < kFloatLanes; ++k) {
            u[k] = unit(random);
            v[k] = k % 4 == 0 ? 0.0f : unit(random);
        }
        int squares[kFloatLanes];
        checkerSquares16(pattern, uv, u, v, squares);
        for (int k = 0; k < kFloatLanes; ++k) {
            // render/SurfacePoint's albedoAtHit for a mesh hit.
            const float w = 1.0f - u[k] - v[k];
            const float texU = uv[0][0] * w + uv[1][0] * u[k] + uv[2][0] * v[k];
            const float texV = uv[0][1] * w + uv[1][1] * u[k] + uv[2][1] * v[k];
            const Rgb expected = texture.sample(texU, texV);
            ASSERT_EQ(expected, squares[k] ? pattern.odd : pattern.even)
                << "block " << block << ", lane " << k << ": " << texU << ", " << texV;
            ASSERT_TRUE(squares[k] == 0 || squares[k] == 1);
            (squares[k] ? odd : even) += 1;
        }
    }
    EXPECT_GT(odd, 10000);
    EXPECT_GT(even, 10000);
}
