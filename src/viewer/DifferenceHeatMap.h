#pragma once
// The viewer's difference view (the quality measures of Ruff 2013): per pixel, the mean
// absolute difference of the displayed (8-bit sRGB) channels of two images,
// in [0, 1], shown as a heat map: blue = same, through cyan, green and
// yellow, to red = totally different.
#include <cstdint>
#include <span>

namespace raycache {

// Heat map color (RGB, 8-bit, display space) of difference d, clamped to [0, 1].
void heatMapColor(float d, std::uint8_t rgb[3]);

// Writes the heat map of `a` against `b` (RGBA8 images of `pixels` pixels,
// as the viewer displays them) into `out` (RGBA8, alpha 255), the difference
// multiplied by `gain` before coloring. Returns the sum over pixels of the
// unscaled differences (divide by the pixel count for the mean).
double differenceHeatMap(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b, float gain,
                         std::span<std::uint8_t> out);

}  // namespace raycache
