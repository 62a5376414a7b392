// cubeTexelIndices16 against the scalar addressing it must equal bit for
// bit (cache/CubeAddressing.h, itself held to OpenGL by
// CubeAddressingGlTest.cpp): random directions of every scale, the ties and
// signed zeros llvmpipe decides, subnormal components, texel edges; lanes
// left out keep what they held. Runs at the widest lane level this
// processor has (LaneLevelsCliTest compares the levels' images).
#include "cache/CubeAddressingLanes.h"

#include <gtest/gtest.h>

#include <array>
#include <cfloat>
#include <cmath>
#include <random>
#include <vector>

#include "cache/CubeAddressing.h"
#include "core/LaneLevels.h"

namespace raycache {
namespace {

int scalarTexel(const Vec3& d, int size) { return cubeTexelIndex(cubeTexelFromDirection(d, size), size); }

// Addresses `directions` sixteen at a time with every lane selected and
// counts the lanes that differ from the scalar texel (reporting the first few).
int mismatches(const std::vector<Vec3>& directions, int size) {
    int wrong = 0;
    for (std::size_t base = 0; base < directions.size(); base += 16) {
        alignas(64) float x[16], y[16], z[16];
        alignas(64) int lanes[16], texels[16];
        for (int k = 0; k < 16; ++k) {
            const Vec3& d = directions[std::min(base + static_cast<std::size_t>(k), directions.size() - 1)];
            x[k] = d.x, y[k] = d.y, z[k] = d.z;
            lanes[k] = -1;
            texels[k] = -7;
        }
        cubeTexelIndices16(x, y, z, size, lanes, texels);
        for (int k = 0; k < 16 && base + static_cast<std::size_t>(k) < directions.size(); ++k) {
            const Vec3& d = directions[base + static_cast<std::size_t>(k)];
            const int expected = scalarTexel(d, size);
            if (texels[k] != expected && ++wrong <= 5)
                ADD_FAILURE() << "size " << size << " (" << d.x << ", " << d.y << ", " << d.z << "): lanes "
                              << texels[k] << ", scalar " << expected;
        }
    }
    return wrong;
}

TEST(CubeAddressingLanes, RandomDirectionsOfEveryScaleMatchTheScalarTexel) {
    std::mt19937 rng(12345);
    std::normal_distribution<float> normal;
    std::uniform_int_distribution<int> exponent(-140, 120);
    std::vector<Vec3> directions;
    for (int i = 0; i < 20000; ++i) {
        const float scale = std::ldexp(1.0f, exponent(rng));
        directions.push_back(Vec3{normal(rng), normal(rng), normal(rng)} * scale);
    }
    for (const int size : {1, 2, 16, 100, 512, 2048}) EXPECT_EQ(mismatches(directions, size), 0) << "size " << size;
    std::printf("lane level: %s\n", laneLevelName(laneLevel()));
}

TEST(CubeAddressingLanes, TiesSignedZerosSubnormalsAndEdgesMatchTheScalarTexel) {
    const float sub = FLT_MIN / 4.0f;  // a subnormal
    const std::array<float, 13> values{0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, sub, -sub, FLT_MIN, -FLT_MIN,
                                       0.999999f, -0.999999f, 1.0e30f};
    std::vector<Vec3> directions;
    for (const float a : values)
        for (const float b : values)
            for (const float c : values) directions.push_back({a, b, c});
    // Directions through texel corners and edges, where rounding decides.
    for (const int size : {2, 100, 512})
        for (int i = 0; i <= size; ++i) {
            const float s = 2.0f * static_cast<float>(i) / static_cast<float>(size) - 1.0f;
            directions.push_back({1.0f, s, s});
            directions.push_back({s, -1.0f, 0.25f});
            directions.push_back({-s, s, -1.0f});
            directions.push_back({std::nextafter(s, 2.0f), 1.0f, std::nextafter(-s, -2.0f)});
        }
    for (const int size : {1, 2, 100, 512, 2048}) EXPECT_EQ(mismatches(directions, size), 0) << "size " << size;
}

TEST(CubeAddressingLanes, LanesLeftOutKeepWhatTheyHeld) {
    alignas(64) float x[16], y[16], z[16];
    alignas(64) int lanes[16], texels[16];
    for (int k = 0; k < 16; ++k) {
        x[k] = 0.1f * static_cast<float>(k) - 0.7f, y[k] = 0.3f, z[k] = -0.9f;
        lanes[k] = k % 3 == 0 ? -1 : 0;
        texels[k] = -1;
    }
    cubeTexelIndices16(x, y, z, 64, lanes, texels);
    for (int k = 0; k < 16; ++k) {
        if (lanes[k]) EXPECT_EQ(texels[k], scalarTexel({x[k], y[k], z[k]}, 64)) << "lane " << k;
        else EXPECT_EQ(texels[k], -1) << "lane " << k;
    }
}

}  // namespace
}  // namespace raycache
