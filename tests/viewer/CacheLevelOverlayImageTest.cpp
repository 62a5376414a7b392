// The cube-level overlay's colours on a hand-made record.
#include "viewer/CacheLevelOverlayImage.h"

#include <gtest/gtest.h>

#include <vector>

using namespace raycache;

namespace {

// blend(c, target) = (c (256 - 160) + target 160) / 256, per channel.
std::vector<int> tinted(int under, std::vector<int> target) {
    for (int& t : target) t = (under * 96 + t * 160) >> 8;
    return target;
}

}  // namespace

TEST(CacheLevelOverlay, EachRecordValueTintsItsPixelWithItsLegendColour) {
    // One pixel per value: no caching ray, traced, levels 0 .. 7; then a
    // second row of the same values reversed.
    CacheLevelImage levels(kMaxCubeLevels + 2, 2);
    for (int x = 0; x < levels.width(); ++x) {
        levels.at(x, 0) = static_cast<std::int8_t>(x - 2);
        levels.at(x, 1) = static_cast<std::int8_t>(levels.width() - 1 - x - 2);
    }
    const std::vector<std::vector<int>> expected = {
        {128, 128, 128},  // no caching ray: grey
        {255, 0, 0},      // traced: red
        {0, 255, 0},      // level 0: green
        {255, 255, 0},    // level 1: yellow
        {255, 128, 0},    // level 2: orange
        {255, 0, 255},    // level 3: magenta
        {0, 96, 255},     // level 4: blue
        {0, 255, 255},    // level 5: cyan
        {255, 255, 255},  // level 6: white
        {128, 0, 255},    // level 7: violet
    };
    ASSERT_EQ(expected.size(), static_cast<std::size_t>(levels.width()));
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(levels.width() * levels.height()) * 4, 100);
    for (std::size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 77;
    paintCacheLevelOverlay(levels, rgba);
    const auto pixel = [&](int x, int y) {
        const std::size_t i = static_cast<std::size_t>(y * levels.width() + x) * 4;
        return std::vector<int>{rgba[i], rgba[i + 1], rgba[i + 2]};
    };
    for (int x = 0; x < levels.width(); ++x) {
        const auto value = static_cast<std::size_t>(x);
        EXPECT_EQ(pixel(x, 0), tinted(100, expected[value])) << "value " << x - 2;
        EXPECT_EQ(pixel(x, 1), tinted(100, expected[expected.size() - 1 - value])) << "value " << levels.at(x, 1);
        // The legend's swatch is the same colour.
        const auto c = cacheLevelColor(static_cast<std::int8_t>(x - 2));
        EXPECT_EQ((std::vector<int>{c[0], c[1], c[2]}), expected[value]);
    }
    for (std::size_t i = 3; i < rgba.size(); i += 4) EXPECT_EQ(rgba[i], 77);  // alpha untouched

    const CacheLevelImage::Counts counts = levels.counts();
    for (const std::int64_t n : counts) EXPECT_EQ(n, 2);
}

TEST(CacheLevelOverlay, NothingIsPaintedWhenTheSizesDiffer) {
    CacheLevelImage levels(3, 2);  // all "no caching ray"
    EXPECT_EQ(levels.counts()[0], 6);
    std::vector<std::uint8_t> rgba(4 * 4, 100);  // a frame of 4 pixels after a resize
    paintCacheLevelOverlay(levels, rgba);
    EXPECT_EQ(rgba, std::vector<std::uint8_t>(16, 100));
}
