#include "cache/CachingCube.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/SharedExponentColor.h"

using namespace raycache;

TEST(SharedExponentColor, RoundTripWithinNineBitPrecision) {
    for (const Rgb c : {Rgb{0.5f, 0.25f, 0.125f}, Rgb{1.0f, 1.0f, 1.0f}, Rgb{0.8f, 0.01f, 0.3f}, Rgb{123.0f, 4.0f, 0.0f},
                        Rgb{1e-4f, 2e-4f, 3e-4f}}) {
        const Rgb d = SharedExponentColor::decode(SharedExponentColor::encode(c));
        // Each channel is within half a step of the largest channel's 9-bit mantissa.
        const float step = std::ldexp(1.0f, std::ilogb(c.maxComponent()) + 1 - 9);
        EXPECT_NEAR(d.r, c.r, 0.5f * step);
        EXPECT_NEAR(d.g, c.g, 0.5f * step);
        EXPECT_NEAR(d.b, c.b, 0.5f * step);
    }
    EXPECT_EQ(SharedExponentColor::decode(SharedExponentColor::encode(Rgb{0.0f})), Rgb{0.0f});
    // Powers of two are exact.
    EXPECT_EQ(SharedExponentColor::decode(SharedExponentColor::encode(Rgb{1.0f, 0.5f, 0.25f})), (Rgb{1.0f, 0.5f, 0.25f}));
}

namespace {

// The encoder as EXT_texture_shared_exponent writes it, with frexp and ldexp:
// the oracle for the bit-twiddled one in core/SharedExponentColor.cpp.
std::uint32_t referenceEncode(const Rgb& color) {
    const auto clampChannel = [](float v) { return !(v > 0.0f) ? 0.0f : std::min(v, SharedExponentColor::kMaxValue); };
    const float r = clampChannel(color.r), g = clampChannel(color.g), b = clampChannel(color.b);
    const float maxChannel = std::max({r, g, b});
    if (maxChannel == 0.0f) return 0u;
    int exponent;
    std::frexp(maxChannel, &exponent);
    int biased = std::max(-16, exponent - 1) + 1 + 15;
    float scale = std::ldexp(1.0f, biased - 15 - 9);
    if (std::floor(maxChannel / scale + 0.5f) >= 512.0f) {
        ++biased;
        scale *= 2.0f;
    }
    biased = std::min(biased, 31);
    const auto mantissa = [&](float v) { return std::min(static_cast<std::uint32_t>(std::floor(v / scale + 0.5f)), 511u); };
    return mantissa(r) | (mantissa(g) << 9) | (mantissa(b) << 18) | (static_cast<std::uint32_t>(biased) << 27);
}

}  // namespace

TEST(SharedExponentColor, EncodesExactlyAsTheSpecificationsFormula) {
    // Every exponent from subnormal to overflow, with mantissas that round up
    // across a power of two, and random colours.
    std::uint32_t state = 12345u;
    const auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return state;
    };
    for (int i = 0; i < 200000; ++i) {
        const float a = std::bit_cast<float>(next() & 0x7fffffffu);
        const float b = std::bit_cast<float>((next() % 0x48000000u));
        const float c = static_cast<float>(next() % 1000u) * 1e-3f;
        const Rgb color = i % 3 == 0 ? Rgb{a, b, c} : i % 3 == 1 ? Rgb{b, c, a} : Rgb{c, a * 1e-30f, b};
        ASSERT_EQ(SharedExponentColor::encode(color), referenceEncode(color)) << color.r << " " << color.g << " " << color.b;
    }
    for (float v : {1e-45f, 1e-38f, 1.5e-5f, 0.99951171875f, 0.999755859375f, 1.0f, 511.5f, 65408.0f, 65500.0f})
        EXPECT_EQ(SharedExponentColor::encode(Rgb{v, v * 0.5f, 0.0f}), referenceEncode(Rgb{v, v * 0.5f, 0.0f})) << v;
}

TEST(SharedExponentColor, ClampsAndNeverProducesTheInvalidWord) {
    const float nan = std::nanf("");
    EXPECT_EQ(SharedExponentColor::decode(SharedExponentColor::encode(Rgb{-1.0f, nan, 0.0f})), Rgb{0.0f});
    for (float v : {65000.0f, 65535.0f, 1e30f, std::numeric_limits<float>::infinity()}) {
        const std::uint32_t packed = SharedExponentColor::encode(Rgb{v});
        EXPECT_NE(packed, SharedExponentColor::kInvalid) << v;
        // Clamped to kMaxValue, then quantized: within one step (2^7 at this exponent).
        EXPECT_NEAR(SharedExponentColor::decode(packed).r, SharedExponentColor::kMaxValue, 128.0f) << v;
    }
}

TEST(CachingCube, StoreThenLookupHitsTheSameTexelOnEveryFace) {
    CachingCube cube({1, 2, 3}, 32);
    EXPECT_EQ(cube.texelCount(), 6u * 32u * 32u);
    EXPECT_EQ(cube.bytes(), 6u * 32u * 32u * 4u);
    const Vec3 directions[] = {{1, 0.3f, -0.2f}, {-1, 0.1f, 0.7f}, {0.2f, 1, -0.4f},
                               {-0.6f, -1, 0.1f}, {0.3f, -0.5f, 1},  {0.05f, 0.2f, -1}};
    for (int f = 0; f < 6; ++f) {
        const Vec3& d = directions[f];
        const int index = cube.texelIndexFor(d);
        EXPECT_EQ(index / (32 * 32), f) << "direction " << f << " addresses the wrong face";
        EXPECT_FALSE(cube.read(index).has_value());
        const Rgb color{0.25f * static_cast<float>(f), 0.5f, 1.0f};
        EXPECT_TRUE(cube.writeIfInvalid(index, CachingCube::encodeTexel(color)));
        // Same direction at another length addresses the same texel.
        const auto back = cube.read(cube.texelIndexFor(d * 7.5f));
        ASSERT_TRUE(back.has_value());
        EXPECT_EQ(*back, color);
    }
    EXPECT_EQ(cube.validCount(), 6u);
}

TEST(CachingCube, ValidTexelsAreNeverOverwrittenUntilCleared) {
    CachingCube cube({0, 0, 0}, 16);
    const int index = cube.texelIndexFor({0, 0, 1});
    EXPECT_TRUE(cube.writeIfInvalid(index, CachingCube::encodeTexel(Rgb{1.0f})));
    EXPECT_FALSE(cube.writeIfInvalid(index, CachingCube::encodeTexel(Rgb{0.5f})));
    EXPECT_EQ(*cube.read(index), Rgb{1.0f});
    cube.clear();
    EXPECT_EQ(cube.validCount(), 0u);
    EXPECT_FALSE(cube.read(index).has_value());
}
