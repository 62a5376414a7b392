#pragma once
// Image difference metrics. Images are compared as displayed: linear values
// clamped to [0,1] and encoded to sRGB, so errors weigh as the eye sees them.
#include <span>

#include "core/Image.h"

namespace raycache {

// Mean absolute difference per channel, in [0,1]. Sizes must match.
double meanAbsoluteError(const Image& a, const Image& b);
// Peak signal-to-noise ratio in dB (peak 1); +infinity for identical images.
double psnr(const Image& a, const Image& b);
// PSNR over the pixels whose `mask` entry (row-major, one per pixel) is not 0:
// +infinity when they are identical, NaN when the mask selects no pixel.
// Throws InputError when the sizes of the images or the mask differ.
double maskedPsnr(const Image& a, const Image& b, std::span<const unsigned char> mask);
// Number of pixels with a NaN or infinite channel.
long countNonFinitePixels(const Image& image);

}  // namespace raycache
