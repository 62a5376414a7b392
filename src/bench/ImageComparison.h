#pragma once
// The three numbers every quality result reports for an image against its
// reference (the uncached render): MAE, PSNR and SSIM of the displayed images.
#include <nlohmann/json.hpp>

#include "core/Image.h"

namespace raycache {

struct ImageComparison {
    double mae = 0.0;   // [0,1], 0 = identical
    double psnr = 0.0;  // dB, +infinity when identical
    double ssim = 1.0;  // 1 = identical
};

ImageComparison compareImages(const Image& image, const Image& reference);
// {"mae", "psnr_db" (null when identical), "ssim"}.
nlohmann::json toJson(const ImageComparison& c);

}  // namespace raycache
