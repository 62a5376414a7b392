// SSIM against values computed by hand from the definition (Wang et al. 2004).
#include <gtest/gtest.h>

#include "core/ColorSpace.h"
#include "core/Errors.h"
#include "metrics/Ssim.h"

using namespace raycache;

namespace {

// A grey image whose displayed (sRGB) value is `display` everywhere.
Image constantDisplay(int w, int h, float display) {
    Image img(w, h);
    for (Rgb& p : img.pixels()) p = Rgb{srgbToLinear(display)};
    return img;
}

}  // namespace

TEST(Ssim, IdenticalImagesScoreExactlyOne) {
    Image a(37, 23);
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            a.at(x, y) = Rgb{static_cast<float>((x * 7 + y * 3) % 11) / 10.0f, static_cast<float>(x) / 37.0f,
                             static_cast<float>(y % 5) / 4.0f};
    EXPECT_EQ(ssim(a, a), 1.0);
    Image small(3, 2);
    small.at(1, 1) = Rgb{0.5f};
    EXPECT_EQ(ssim(small, small), 1.0);
}

TEST(Ssim, ConstantImagesKeepOnlyTheLuminanceTerm) {
    // Zero variance: SSIM = (2 mx my + C1) / (mx^2 + my^2 + C1) with C1 = 0.01^2,
    // here 0.2501 / 0.3126, in every 11x11 window.
    const Image a = constantDisplay(16, 16, 0.5f), b = constantDisplay(16, 16, 0.25f);
    EXPECT_NEAR(ssim(a, b), 0.2501 / 0.3126, 1e-6);
}

TEST(Ssim, KnownPairInOneWholeImageWindow) {
    // 2x2 grey images (smaller than the window: one uniform window).
    // x = 0 1 / 0 1, y = 0 1 / 1 1 (displayed values).
    // mx = 0.5, my = 0.75, var x = 0.25, var y = 0.1875, cov = 0.125, so
    // SSIM = (2*0.5*0.75 + 1e-4)(2*0.125 + 9e-4) / ((0.25 + 0.5625 + 1e-4)(0.25 + 0.1875 + 9e-4)).
    Image x(2, 2), y(2, 2);
    x.at(1, 0) = x.at(1, 1) = Rgb{1.0f};
    y.at(1, 0) = y.at(0, 1) = y.at(1, 1) = Rgb{1.0f};
    const double expected = (0.7501 * 0.2509) / (0.8126 * 0.4384);
    EXPECT_NEAR(ssim(x, y), expected, 1e-9);
    EXPECT_NEAR(ssim(y, x), expected, 1e-9);  // symmetric
}

TEST(Ssim, InvertedStripesAreAntiCorrelated) {
    // Columns alternating 0/1 against their inverse: covariance = -variance in
    // every window, so SSIM is close to -1.
    Image a(24, 24), b(24, 24);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
            a.at(x, y) = Rgb{static_cast<float>(x % 2)};
            b.at(x, y) = Rgb{static_cast<float>(1 - x % 2)};
        }
    EXPECT_LT(ssim(a, b), -0.95);
}

TEST(Ssim, FormulaFromStatistics) {
    EXPECT_DOUBLE_EQ(ssimFromStatistics(0.5, 0.5, 0.1, 0.1, 0.1), 1.0);
    EXPECT_NEAR(ssimFromStatistics(0.5, 0.75, 0.25, 0.1875, 0.125), (0.7501 * 0.2509) / (0.8126 * 0.4384), 1e-12);
}

TEST(Ssim, RejectsMismatchedOrEmptyImages) {
    EXPECT_THROW(ssim(Image(4, 4), Image(4, 5)), InputError);
    EXPECT_THROW(ssim(Image(), Image()), InputError);
}
