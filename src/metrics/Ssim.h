#pragma once
// Structural similarity (Wang, Bovik, Sheikh, Simoncelli 2004), as the image
// quality literature reports it: an 11x11 Gaussian window (sigma 1.5) slid
// over every position where it fits inside the image, K1 = 0.01, K2 = 0.03,
// dynamic range 1. Like the other metrics (ImageMetrics.h) it compares the
// images as displayed: linear values clamped to [0,1] and encoded to sRGB;
// each RGB channel is scored separately and the three means are averaged.
#include "core/Image.h"

namespace raycache {

struct SsimSettings {
    int windowSize = 11;  // odd; images smaller than this use one window over the whole image
    double sigma = 1.5;   // Gaussian weights; <= 0 gives uniform weights
    double k1 = 0.01;
    double k2 = 0.03;
};

// SSIM of one window given its weighted statistics: the formula itself, for
// callers and tests that have the statistics at hand.
double ssimFromStatistics(double meanX, double meanY, double varianceX, double varianceY, double covariance,
                          const SsimSettings& settings = {});

// Mean SSIM of two images of the same size, in [-1, 1]; exactly 1 for
// identical images. Images smaller than the window in either direction are
// scored with one window covering the whole image, weighted uniformly.
// Throws InputError if the sizes differ or an image is empty.
double ssim(const Image& a, const Image& b, const SsimSettings& settings = {});

}  // namespace raycache
