#pragma once
// The exact sRGB transfer function (IEC 61966-2-1), for 8-bit image I/O.
#include <algorithm>
#include <cmath>

namespace raycache {

// Evaluated in double so that 0 and 1 map exactly onto 0 and 1 after rounding to float.
inline float srgbToLinear(float encoded) {
    const double v = encoded;
    if (v <= 0.04045) return static_cast<float>(v / 12.92);
    return static_cast<float>(std::pow((v + 0.055) / 1.055, 2.4));
}

inline float linearToSrgb(float linear) {
    const double v = linear;
    if (v <= 0.0031308) return static_cast<float>(v * 12.92);
    return static_cast<float>(1.055 * std::pow(v, 1.0 / 2.4) - 0.055);
}

// A linear value as a display shows it, clamped to [0, 1] then sRGB-encoded:
// what the image metrics (PSNR, SSIM, heat maps) compare.
inline float displayedValue(float linear) { return linearToSrgb(std::clamp(linear, 0.0f, 1.0f)); }

// The 8-bit sRGB code of a linear value, as PNG files and the viewer show it:
// clamped to [0, 1], NaN as 0.
inline unsigned char linearToSrgb8(float linear) {
    // NaN would make the conversion to an integer undefined; treat it as black.
    if (!(linear > 0.0f)) return 0;
    const float encoded = std::min(linearToSrgb(linear), 1.0f);
    return static_cast<unsigned char>(std::lround(encoded * 255.0f));
}

}  // namespace raycache
