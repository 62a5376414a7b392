// `--spp N` (render/PixelSamples.h, render/PixelFilter.h, render/FilteredFilm.h):
// the filter against its definition, an edge against its analytic coverage,
// and the ray pipeline's anti-aliased frames against thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

#include "ImageCompare.h"
#include "core/Parallel.h"
#include "render/FilteredFilm.h"
#include "render/PixelFilter.h"
#include "render/PixelSamples.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

// Midpoint-rule integral of f over [a, b].
template <class F>
double integrate(F f, double a, double b, int steps = 4000) {
    double sum = 0.0;
    const double h = (b - a) / steps;
    for (int i = 0; i < steps; ++i) sum += f(a + (i + 0.5) * h);
    return sum * h;
}

}  // namespace

TEST(PixelFilter, IsCyclesBlackmanHarrisOverThreePixels) {
    // Cycles' filter_func_blackman_harris(v, width) with its table's width
    // doubled: 1.5 px filter width reaches 1.5 px either side.
    const auto cycles = [](double v) {
        const double width = 2.0 * 1.5;
        const double x = 2.0 * M_PI * (v / width + 0.5);
        return 0.35875 - 0.48829 * std::cos(x) + 0.14128 * std::cos(2.0 * x) - 0.01168 * std::cos(3.0 * x);
    };
    for (double d = -1.5; d <= 1.5; d += 0.125)
        EXPECT_NEAR(PixelFilter::weight1d(static_cast<float>(d)), std::fabs(d) < 1.5 ? cycles(d) : 0.0, 1e-6) << d;
    EXPECT_EQ(PixelFilter::weight1d(1.5f), 0.0f);
    EXPECT_EQ(PixelFilter::weight1d(-2.0f), 0.0f);
    EXPECT_NEAR(PixelFilter::weight1d(0.0f), 1.0, 1e-6);  // the window's peak
}

// The weights each output pixel gathers are normalised: a flat layer, however
// its samples lie, resolves to its value in every pixel, edges included.
TEST(FilteredFilm, WeightsAreNormalised) {
    const Parallel parallel(2);
    const PixelSamples samples(9);
    FilteredFilm film(13, 7);
    Image layer(13, 7);
    for (Rgb& p : layer.pixels()) p = Rgb(0.375f);
    for (int s = 0; s < samples.count(); ++s) film.addLayer(layer, samples, s, parallel);
    Image out;
    film.resolve(out, parallel);
    for (const Rgb& p : out.pixels()) EXPECT_NEAR(p.r, 0.375f, 1e-6f);
}

TEST(PixelSamples, AreStratifiedAndFixed) {
    const PixelSamples samples(16);
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{5, 9}, std::pair{511, 3}}) {
        std::set<std::pair<int, int>> strata;
        for (int s = 0; s < 16; ++s) {
            const PixelOffset o = samples.offset(x, y, s);
            ASSERT_GE(o.x, 0.0f);
            ASSERT_LE(o.x, 1.0f);
            ASSERT_GE(o.y, 0.0f);
            ASSERT_LE(o.y, 1.0f);
            strata.insert({static_cast<int>(o.x * 4.0f), static_cast<int>(o.y * 4.0f)});
            EXPECT_EQ(o.x, PixelSamples(16).offset(x, y, s).x);  // a fixed sequence
        }
        EXPECT_EQ(strata.size(), 16u);  // one sample in each of the 4 x 4 strata
    }
    // Neighbouring pixels do not share their jitter.
    EXPECT_NE(samples.offset(3, 3, 0).x, samples.offset(4, 3, 0).x);
}

// A tilted edge: the half-plane a·x + b·y < c (pixel units) is white. With 16
// samples each pixel's value comes close to the filter-weighted area of the
// half-plane under its window, computed here by numerical integration.
TEST(FilteredFilm, AnEdgeGetsItsFilterWeightedCoverage) {
    const int width = 24, height = 24;
    const double a = std::cos(0.3), b = std::sin(0.3), c = 12.3;
    const auto inside = [&](double x, double y) { return a * x + b * y < c; };
    const Parallel parallel(2);
    const PixelSamples samples(16);
    FilteredFilm film(width, height);
    Image layer(width, height);
    for (int s = 0; s < samples.count(); ++s) {
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const PixelOffset o = samples.offset(x, y, s);
                layer.at(x, y) = Rgb(inside(static_cast<double>(x) + o.x, static_cast<double>(y) + o.y) ? 1.0f : 0.0f);
            }
        film.addLayer(layer, samples, s, parallel);
    }
    Image out;
    film.resolve(out, parallel);
    const auto w = [](double d) { return static_cast<double>(PixelFilter::weight1d(static_cast<float>(d))); };
    const double r = PixelFilter::kRadius;
    const double norm = std::pow(integrate(w, -r, r), 2.0);
    double worst = 0.0, edgePixels = 0.0, signedSum = 0.0, squaredSum = 0.0, centreSquaredSum = 0.0;
    for (int y = 3; y < height - 3; ++y)
        for (int x = 3; x < width - 3; ++x) {
            const double cx = x + 0.5, cy = y + 0.5;
            const double covered = integrate(
                [&](double dy) {
                    return w(dy) * integrate([&](double dx) { return inside(cx + dx, cy + dy) ? w(dx) : 0.0; }, -r,
                                             r, 200);
                },
                -r, r, 200) / norm;
            const double got = out.at(x, y).r;
            worst = std::max(worst, std::fabs(got - covered));
            if (!(covered > 0.02 && covered < 0.98)) continue;
            edgePixels += 1.0;
            signedSum += got - covered;
            squaredSum += (got - covered) * (got - covered);
            // One ray through the centre, as --spp 1 renders.
            const double centre = inside(cx, cy) ? 1.0 : 0.0;
            centreSquaredSum += (centre - covered) * (centre - covered);
        }
    ASSERT_GT(edgePixels, 20.0);  // the edge crosses the tested pixels
    const double rms = std::sqrt(squaredSum / edgePixels), centreRms = std::sqrt(centreSquaredSum / edgePixels);
    std::printf("edge pixels %.0f: mean error %.4f, rms %.4f, worst %.4f; centre rays rms %.4f\n", edgePixels,
                signedSum / edgePixels, rms, worst, centreRms);
    EXPECT_LT(std::fabs(signedSum / edgePixels), 0.02);  // no bias
    EXPECT_LT(rms, 0.05);
    EXPECT_LT(worst, 0.15);
    EXPECT_LT(rms, centreRms / 4.0);
}

// The ray pipeline's --spp frames: the same bits on one and two threads.
TEST(AntiAliasing, FramesDoNotDependOnTheThreadCount) {
    const auto scene = makeBuiltinScene("room");
    ASSERT_TRUE(scene.has_value());
    RenderSettings settings;
    settings.width = 40;
    settings.height = 32;
    settings.samplesPerPixel = 4;
    settings.cache.resolutionOverride = 32;
    Image images[2];
    for (int threads : {1, 2}) {
        settings.threads = threads;
        RenderSession session(*scene, settings);
        session.render(scene->camera, images[threads - 1]);
    }
    EXPECT_TRUE(identicalImages(images[0], images[1]));
    // ...and differ from one ray through each pixel's centre.
    settings.samplesPerPixel = 1;
    RenderSession centres(*scene, settings);
    Image one;
    centres.render(scene->camera, one);
    EXPECT_FALSE(identicalImages(one, images[0]));
}
