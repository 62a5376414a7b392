// The viewer shows exactly the 8-bit sRGB codes a PNG of the same film holds.
#include "viewer/Srgb8Encoder.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <limits>

#include "core/ColorSpace.h"

using namespace raycache;

TEST(Srgb8Encoder, MatchesLinearToSrgb8AcrossTheWholeDisplayRange) {
    const Srgb8Encoder encoder;
    // Every 37th float from 0 to 2 (~0.7 % of them, spread over every exponent).
    const std::uint32_t end = std::bit_cast<std::uint32_t>(2.0f);
    for (std::uint32_t bits = 0; bits < end; bits += 37) {
        const float v = std::bit_cast<float>(bits);
        ASSERT_EQ(encoder.encode(v), linearToSrgb8(v)) << v;
    }
}

TEST(Srgb8Encoder, MatchesAtEveryThresholdAndItsNeighbours) {
    const Srgb8Encoder encoder;
    for (int code = 1; code <= 255; ++code) {
        const float t = encoder.threshold(code);
        EXPECT_EQ(linearToSrgb8(t), code);  // the threshold is where the code starts...
        const float below = std::nextafter(t, 0.0f);
        EXPECT_EQ(linearToSrgb8(below), code - 1);  // ...and not one float earlier
        for (float v : {below, t, std::nextafter(t, 2.0f)}) EXPECT_EQ(encoder.encode(v), linearToSrgb8(v)) << v;
    }
}

TEST(Srgb8Encoder, SpecialValues) {
    const Srgb8Encoder encoder;
    const float inf = std::numeric_limits<float>::infinity();
    for (float v : {0.0f, -0.0f, -1.0f, -inf, inf, std::numeric_limits<float>::quiet_NaN(), 1.0f, 1e30f,
                    std::numeric_limits<float>::denorm_min()})
        EXPECT_EQ(encoder.encode(v), linearToSrgb8(v)) << v;
    EXPECT_EQ(encoder.encode(inf), 255);
    EXPECT_EQ(encoder.encode(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(Srgb8Encoder, EncodeRowsWritesRgbaRowMajor) {
    const Srgb8Encoder encoder;
    Image image(3, 2);
    image.at(2, 1) = Rgb{1.0f, 0.5f, 0.0f};
    std::vector<std::uint8_t> rgba(3 * 2 * 4, 7);
    encoder.encodeRows(image, 0, 2, rgba);
    const std::size_t i = (1 * 3 + 2) * 4;
    EXPECT_EQ(rgba[i], 255);
    EXPECT_EQ(rgba[i + 1], linearToSrgb8(0.5f));
    EXPECT_EQ(rgba[i + 2], 0);
    EXPECT_EQ(rgba[i + 3], 255);
    EXPECT_EQ(rgba[0], 0);
    EXPECT_EQ(rgba[3], 255);
}

// Screenshots are read back as 8-bit codes and written through the linear
// image writer: every code must come back unchanged.
TEST(Srgb8Encoder, EightBitCodesSurviveTheRoundTripThroughLinear) {
    for (int code = 0; code < 256; ++code)
        EXPECT_EQ(linearToSrgb8(srgbToLinear(static_cast<float>(code) / 255.0f)), code);
}
