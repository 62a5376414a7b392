// Exposure and the view transforms (core/DisplayTransform.h, core/ViewTransform.h)
// against their published definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string_view>

#include "core/ColorSpace.h"
#include "core/DisplayTransform.h"
#include "core/ViewTransform.h"

using namespace raycache;

namespace {

// The Khronos PBR Neutral specification (KhronosGroup/ToneMapping,
// PBR_Neutral/README.md) written out in double, term for term.
std::array<double, 3> pbrNeutralSpec(std::array<double, 3> c) {
    const double f90 = 0.04, ks = 0.8 - f90, kd = 0.15;
    const double x = std::min({c[0], c[1], c[2]});
    const double f = x <= 2.0 * f90 ? x - x * x / (4.0 * f90) : f90;
    const double p = std::max({c[0] - f, c[1] - f, c[2] - f});
    std::array<double, 3> out{};
    if (p <= ks) {
        for (int i = 0; i < 3; ++i) out[i] = c[i] - f;
        return out;
    }
    const double pn = 1.0 - (1.0 - ks) * (1.0 - ks) / (p + 1.0 - 2.0 * ks);
    const double g = 1.0 / (kd * (p - pn) + 1.0);
    for (int i = 0; i < 3; ++i) out[i] = (c[i] - f) * pn / p * g + pn * (1.0 - g);
    return out;
}

}  // namespace

TEST(ViewTransform, KhronosPbrNeutralMatchesItsSpecification) {
    const std::array<std::array<double, 3>, 9> inputs{{{0.0, 0.0, 0.0},
                                                       {0.02, 0.05, 0.07},
                                                       {0.18, 0.18, 0.18},
                                                       {0.5, 0.2, 0.1},
                                                       {0.7, 0.75, 0.79},
                                                       {1.0, 1.0, 1.0},
                                                       {3.0, 0.5, 0.1},
                                                       {10.0, 20.0, 5.0},
                                                       {100.0, 100.0, 100.0}}};
    for (const auto& in : inputs) {
        const auto want = pbrNeutralSpec(in);
        const Rgb got = applyViewTransform(
            ViewTransform::KhronosPbrNeutral,
            {static_cast<float>(in[0]), static_cast<float>(in[1]), static_cast<float>(in[2])});
        EXPECT_NEAR(got.r, want[0], 2e-6) << in[0];
        EXPECT_NEAR(got.g, want[1], 2e-6) << in[1];
        EXPECT_NEAR(got.b, want[2], 2e-6) << in[2];
    }
}

TEST(ViewTransform, EveryTransformMapsBlackToBlackIsMonotoneAndStaysInRange) {
    for (const ViewTransform t : kViewTransforms) {
        const Rgb black = applyViewTransform(t, Rgb(0.0f));
        EXPECT_EQ(linearToSrgb8(black.r), 0) << viewTransformName(t);
        if (t == ViewTransform::KhronosPbrNeutral || t == ViewTransform::Standard) {
            EXPECT_EQ(black.r, 0.0f);
        }
        float last = -1.0f;
        for (double ev = -14.0; ev <= 8.0; ev += 1.0 / 16.0) {
            const float v = applyViewTransform(t, Rgb(static_cast<float>(std::exp2(ev)))).g;
            EXPECT_GE(v, last) << viewTransformName(t) << " at " << ev << " EV";
            if (t != ViewTransform::Standard) {
                EXPECT_GE(v, 0.0f);
                EXPECT_LE(v, 1.0f);
            }
            last = v;
        }
        // NaN and negative light show as black, not as NaN.
        const Rgb bad = applyViewTransform(t, {std::nanf(""), -1.0f, 0.0f});
        EXPECT_EQ(linearToSrgb8(bad.r), 0) << viewTransformName(t);
        EXPECT_EQ(linearToSrgb8(bad.g), 0) << viewTransformName(t);
    }
}

// Known values of Blender's curves: Filmic's base contrast puts scene middle
// grey (0.18) at the log encoding's 0.606 where the curve file
// (filmic_to_0-70_1-03.spi1d) reads 0.4998 (sRGB-encoded); AgX's log
// encoding puts 0.18 at 0.606 too, where the minimal AgX polynomial reads
// 0.4982 (for grey the inset and outset matrices cancel: rows sum to 1).
TEST(ViewTransform, FilmicAndAgxPutMiddleGreyWhereBlendersCurvesDo) {
    const float filmicGrey = linearToSrgb(applyViewTransform(ViewTransform::Filmic, Rgb(0.18f)).g);
    EXPECT_NEAR(filmicGrey, 0.4998, 1.0 / 255.0);
    const double x = (std::log2(0.18) + 12.47393) / (4.026069 + 12.47393);
    const double x2 = x * x, x4 = x2 * x2;
    const double agxCurve =
        15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
    const float agxGrey = linearToSrgb(applyViewTransform(ViewTransform::Agx, Rgb(0.18f)).g);
    EXPECT_NEAR(agxGrey, agxCurve, 2e-3);
}

TEST(DisplayTransform, OneStopDoublesTheLightBeforeTheTransform) {
    for (const ViewTransform t : kViewTransforms) {
        const DisplayTransform plus1({.exposure = 1.0f, .view = t});
        const DisplayTransform zero({.exposure = 0.0f, .view = t});
        for (const float v : {0.01f, 0.1f, 0.3f, 2.0f}) {
            const Rgb exposed = plus1(Rgb(v));
            const Rgb doubled = zero(Rgb(2.0f * v));
            EXPECT_EQ(exposed.r, doubled.r) << viewTransformName(t) << " " << v;
        }
    }
    const DisplayTransform minus2({.exposure = -2.0f});
    EXPECT_EQ(minus2(Rgb(0.8f)).r, 0.2f);
}

TEST(DisplayTransform, DefaultsShowTheFilmAsItIs) {
    const DisplayTransform standard{DisplaySettings{}};
    EXPECT_TRUE(standard.identity());
    for (const float v : {-1.0f, 0.0f, 0.25f, 1.0f, 7.5f}) EXPECT_EQ(standard(Rgb(v)).r, v);
    EXPECT_FALSE(DisplayTransform({.exposure = 0.5f}).identity());
    EXPECT_FALSE(DisplayTransform({.view = ViewTransform::Agx}).identity());
}

// The command line and the scene files take a transform by its name: each
// has its own.
TEST(ViewTransform, EveryTransformHasANameOfItsOwn) {
    std::set<std::string_view> names;
    for (const ViewTransform t : kViewTransforms) EXPECT_TRUE(names.insert(viewTransformName(t)).second) << viewTransformName(t);
    EXPECT_EQ(names.count("?"), 0u);
}
