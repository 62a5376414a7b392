#include "core/ViewTransform.h"

#include <algorithm>
#include <cmath>

#include "core/ColorSpace.h"

namespace raycache {

namespace {

// NaN and negative light count as none.
float lightOrNone(float v) { return v > 0.0f ? v : 0.0f; }

// Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral/README.md), term
// for term: F90 = 0.04, Ks = 0.8 - F90, Kd = 0.15.
Rgb khronosPbrNeutral(Rgb c) {
    constexpr float kStartCompression = 0.8f - 0.04f;
    constexpr float kDesaturation = 0.15f;
    const float x = std::min(c.r, std::min(c.g, c.b));
    const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    c.r -= offset, c.g -= offset, c.b -= offset;
    const float peak = c.maxComponent();
    if (peak < kStartCompression) return c;
    constexpr float d = 1.0f - kStartCompression;
    const float newPeak = 1.0f - d * d / (peak + d - kStartCompression);
    c *= newPeak / peak;
    const float g = 1.0f - 1.0f / (kDesaturation * (peak - newPeak) + 1.0f);
    // mix(c, newPeak, g)
    return {c.r + (newPeak - c.r) * g, c.g + (newPeak - c.g) * g, c.b + (newPeak - c.b) * g};
}

// Blender's log encodings: log2 of the light between these exposures mapped
// onto [0, 1] (AgX's and Filmic's shaper: 16.5 stops around 0.18).
constexpr double kLogMinEv = -12.47393;
constexpr double kLogMaxEv = 4.026069;

double logEncoded(double v, double lo, double hi) {
    const double ev = std::clamp(std::log2(std::max(v, 1e-10)), lo, hi);
    return (ev - lo) / (hi - lo);
}

// "Minimal AgX" (Benjamin Wrensch, iolite-engine.com/blog_posts/minimal_agx_implementation,
// 2024): Troy Sobotka's AgX inset matrix, the log2 encoding, and a 6th-order
// polynomial fit of AgX's default contrast sigmoid. The result is display-encoded.
double agxContrast(double x) {
    const double x2 = x * x, x4 = x2 * x2;
    return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
}

Rgb agx(const Rgb& c) {
    const double r = c.r, g = c.g, b = c.b;
    // The inset matrix (rows: output channels).
    const double ir = 0.842479062253094 * r + 0.0784335999999992 * g + 0.0792237451477643 * b;
    const double ig = 0.0423282422610123 * r + 0.878468636469772 * g + 0.0791661274605434 * b;
    const double ib = 0.0423756549057051 * r + 0.0784336 * g + 0.879142973793104 * b;
    const double er = agxContrast(logEncoded(ir, kLogMinEv, kLogMaxEv));
    const double eg = agxContrast(logEncoded(ig, kLogMinEv, kLogMaxEv));
    const double eb = agxContrast(logEncoded(ib, kLogMinEv, kLogMaxEv));
    // The outset (the inset's inverse), clamped to the display's range.
    const auto out = [](double v) { return srgbToLinear(static_cast<float>(std::clamp(v, 0.0, 1.0))); };
    return {out(1.19687900512017 * er - 0.0980208811401368 * eg - 0.0990297440797205 * eb),
            out(-0.0528968517574562 * er + 1.15190312990417 * eg - 0.0989611768448433 * eb),
            out(-0.0529716355144438 * er - 0.0980434501171241 * eg + 1.15107367264116 * eb)};
}

// Blender 3.x's Filmic, "Base Contrast" look (its OCIO config): the log2
// encoding above (its lg2 allocation [-12.473931188, 12.526068812] then the
// uniform allocation [0, 0.66], i.e. 16.5 stops up to +4.03 EV), then the 1D
// curve filmic_to_0-70_1-03.spi1d to the sRGB display encoding. The curve is
// a least-squares Chebyshev fit of degree 10 to the 4096 entries of that file
// (scripts/fit-filmic-curve.py; at most 0.22 of an 8-bit code away). The
// 65³ desaturation cube Filmic applies before the curve is not reproduced:
// bright saturated colours stay more saturated than in Blender.
constexpr std::array<double, 11> kFilmicChebyshev{
    0.43505086520960234,   0.5740428728641999,     0.09597074874532355,  -0.08440733184178752,
    -0.040358683328348154, 0.01065434661872064,    0.011799301371216807, -0.0002101369710568061,
    -0.0027724685136629565, -0.0005892421798637967, 0.0006547066038478986};

double filmicSeries(double logValue) {
    // Clenshaw's recurrence for the Chebyshev series at t in [-1, 1].
    const double t = 2.0 * logValue - 1.0;
    double b1 = 0.0, b2 = 0.0;
    for (std::size_t k = kFilmicChebyshev.size() - 1; k >= 1; --k) {
        const double b0 = kFilmicChebyshev[k] + 2.0 * t * b1 - b2;
        b2 = b1;
        b1 = b0;
    }
    return kFilmicChebyshev[0] + t * b1 - b2;
}

// The fit dips by a fifth of an 8-bit code below log value 0.00885 (where
// the curve file is flat at 0): there a straight line from 0 to the fit
// keeps the curve monotone and black black.
double filmicCurve(double logValue) {
    constexpr double kToeEnd = 0.00885;
    if (logValue >= kToeEnd) return filmicSeries(logValue);
    return filmicSeries(kToeEnd) * logValue / kToeEnd;
}

float filmicChannel(float v) {
    const double encoded = std::clamp(filmicCurve(logEncoded(v, -12.473931188, 4.026068812)), 0.0, 1.0);
    return srgbToLinear(static_cast<float>(encoded));
}

}  // namespace

Rgb applyViewTransform(ViewTransform transform, const Rgb& sceneLinear) {
    if (transform == ViewTransform::Standard) return sceneLinear;
    const Rgb c{lightOrNone(sceneLinear.r), lightOrNone(sceneLinear.g), lightOrNone(sceneLinear.b)};
    switch (transform) {
        case ViewTransform::Filmic: return {filmicChannel(c.r), filmicChannel(c.g), filmicChannel(c.b)};
        case ViewTransform::Agx: return agx(c);
        case ViewTransform::KhronosPbrNeutral: return khronosPbrNeutral(c);
        case ViewTransform::Standard: break;
    }
    return c;
}

}  // namespace raycache
