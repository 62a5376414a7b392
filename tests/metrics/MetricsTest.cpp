#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/SampleSummary.h"
#include "metrics/ImageMetrics.h"

using namespace raycache;

TEST(SampleSummary, MedianAndRange) {
    const std::vector<double> odd{5, 1, 3}, even{4, 1, 3, 2};
    EXPECT_DOUBLE_EQ(summarize(odd).median, 3.0);
    EXPECT_DOUBLE_EQ(summarize(even).median, 2.5);
    EXPECT_DOUBLE_EQ(summarize(even).min, 1.0);
    EXPECT_DOUBLE_EQ(summarize(even).max, 4.0);
    EXPECT_DOUBLE_EQ(summarize({}).median, 0.0);
}

TEST(ImageMetrics, PsnrAndMaeOfKnownImages) {
    // Display values: linear 0 and 1 encode to sRGB 0 and 1 exactly.
    Image black(4, 2), white(4, 2), half(4, 2);
    for (Rgb& p : white.pixels()) p = Rgb{1.0f};
    // Half the pixels differ by 1 in every channel: MSE = 0.5, PSNR = 10 log10(2).
    for (int x = 0; x < 4; ++x) half.at(x, 0) = Rgb{1.0f};
    EXPECT_NEAR(psnr(black, half), 10.0 * std::log10(2.0), 1e-12);
    EXPECT_NEAR(meanAbsoluteError(black, half), 0.5, 1e-12);
    EXPECT_DOUBLE_EQ(psnr(black, white), 0.0);
    EXPECT_EQ(psnr(white, white), std::numeric_limits<double>::infinity());
    EXPECT_DOUBLE_EQ(meanAbsoluteError(white, white), 0.0);
}

TEST(ImageMetrics, MaskedPsnrCountsOnlyMaskedPixels) {
    Image black(4, 2), half(4, 2);
    for (int x = 0; x < 4; ++x) half.at(x, 0) = Rgb{1.0f};
    // Row 0 differs by 1 everywhere, row 1 is the same.
    std::vector<unsigned char> rowZero(8, 0), rowOne(8, 0), both(8, 1), none(8, 0);
    for (int x = 0; x < 4; ++x) rowZero[static_cast<std::size_t>(x)] = rowOne[static_cast<std::size_t>(4 + x)] = 1;
    EXPECT_DOUBLE_EQ(maskedPsnr(black, half, rowZero), 0.0);
    EXPECT_EQ(maskedPsnr(black, half, rowOne), std::numeric_limits<double>::infinity());
    EXPECT_NEAR(maskedPsnr(black, half, both), psnr(black, half), 1e-12);
    EXPECT_TRUE(std::isnan(maskedPsnr(black, half, none)));
    EXPECT_THROW(maskedPsnr(black, half, std::vector<unsigned char>(7, 1)), std::exception);
}

TEST(ImageMetrics, CountsNonFinitePixels) {
    Image img(3, 1);
    img.at(1, 0) = Rgb{std::nanf(""), 0.0f, 0.0f};
    img.at(2, 0) = Rgb{0.0f, std::numeric_limits<float>::infinity(), 0.0f};
    EXPECT_EQ(countNonFinitePixels(img), 2);
}
