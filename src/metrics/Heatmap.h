#pragma once
// Difference heat maps as the documents show them (the thesis's quality figures): the
// per-pixel absolute RGB difference of two images as displayed, colored from
// blue (same) through cyan, green and yellow to red (totally different), with
// a labelled color bar beside the picture.
#include <vector>

#include "core/Image.h"
#include "core/Rgb.h"

namespace raycache {

struct HeatmapSettings {
    // The difference shown as full red. 1 is the documents' scale (red =
    // totally different); a smaller value stretches small differences.
    double maxDifference = 1.0;
};

// Per pixel, the mean over R, G, B of |a - b| after clamping to [0,1] and
// sRGB encoding, in [0,1]; row-major, a.width() x a.height(). Throws
// InputError if the sizes differ.
std::vector<float> pixelDifferences(const Image& a, const Image& b);

// The display (sRGB-encoded) color of t in [0,1] on the blue-to-red scale;
// t outside [0,1] is clamped.
Rgb heatColorDisplay(double t);

// The heat map of a against b with the color bar on its right, as a linear
// image ready for writeImage (PNG shows exactly the scale's colors). Throws
// InputError if the sizes differ, an image is empty or maxDifference <= 0.
Image renderHeatmap(const Image& a, const Image& b, const HeatmapSettings& settings = {});

}  // namespace raycache
