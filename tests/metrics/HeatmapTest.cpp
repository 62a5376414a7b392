#include <gtest/gtest.h>

#include "core/Errors.h"
#include "metrics/Heatmap.h"

using namespace raycache;

TEST(Heatmap, ColorScaleRunsFromBlueToRed) {
    const Rgb same = heatColorDisplay(0.0), middle = heatColorDisplay(0.5), different = heatColorDisplay(1.0);
    EXPECT_EQ(same.r, 0.0f);
    EXPECT_EQ(same.g, 0.0f);
    EXPECT_EQ(same.b, 1.0f);
    EXPECT_EQ(middle.r, 0.0f);
    EXPECT_EQ(middle.g, 1.0f);
    EXPECT_EQ(middle.b, 0.0f);
    EXPECT_EQ(different.r, 1.0f);
    EXPECT_EQ(different.g, 0.0f);
    EXPECT_EQ(different.b, 0.0f);
    const Rgb clamped = heatColorDisplay(7.0);
    EXPECT_EQ(clamped.r, 1.0f);
}

TEST(Heatmap, PixelDifferenceIsTheMeanAbsoluteChannelDifference) {
    Image a(2, 1), b(2, 1);
    b.at(0, 0) = Rgb{1.0f, 0.0f, 0.0f};  // one channel of three fully different
    b.at(1, 0) = Rgb{1.0f};              // all three
    const std::vector<float> d = pixelDifferences(a, b);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_NEAR(d[0], 1.0f / 3.0f, 1e-7);
    EXPECT_NEAR(d[1], 1.0f, 1e-7);
}

TEST(Heatmap, PictureAndColorBar) {
    Image a(40, 30), b(40, 30);
    b.at(5, 5) = Rgb{1.0f};  // one totally different pixel
    const Image map = renderHeatmap(a, b);
    ASSERT_GE(map.height(), 30);  // taller when the bar needs room for its labels
    ASSERT_GT(map.width(), 40);   // the color bar sits on the right
    // Same pixels blue, the different one red (display colors 0/1 are exact in linear).
    EXPECT_EQ(map.at(0, 0).b, 1.0f);
    EXPECT_EQ(map.at(0, 0).r, 0.0f);
    EXPECT_EQ(map.at(5, 5).r, 1.0f);
    EXPECT_EQ(map.at(5, 5).b, 0.0f);
    // The bar: red at its top, blue at its bottom, in a column right of the picture.
    bool foundBar = false;
    for (int x = 40; x < map.width() && !foundBar; ++x) {
        const Rgb top = map.at(x, 4), bottom = map.at(x, map.height() - 5);
        foundBar = top.r == 1.0f && top.g == 0.0f && top.b == 0.0f && bottom.r == 0.0f && bottom.b == 1.0f;
    }
    EXPECT_TRUE(foundBar);
}

TEST(Heatmap, ScaleStretchesSmallDifferences) {
    Image a(12, 12), b(12, 12);
    b.at(3, 3) = Rgb{0.25f, 0.25f, 0.25f};
    // Displayed 0.25 linear is ~0.537; at scale 0.5 it saturates to red.
    EXPECT_EQ(renderHeatmap(a, b, {0.5}).at(3, 3).r, 1.0f);
    EXPECT_LT(renderHeatmap(a, b, {1.0}).at(3, 3).r, 1.0f);
    EXPECT_THROW(renderHeatmap(a, b, {0.0}), InputError);
    EXPECT_THROW(renderHeatmap(a, Image(3, 3)), InputError);
}
