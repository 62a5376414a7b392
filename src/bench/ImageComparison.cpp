#include "bench/ImageComparison.h"

#include "bench/ResultsJson.h"
#include "metrics/ImageMetrics.h"
#include "metrics/Ssim.h"

namespace raycache {

ImageComparison compareImages(const Image& image, const Image& reference) {
    return {meanAbsoluteError(image, reference), psnr(image, reference), ssim(image, reference)};
}

nlohmann::json toJson(const ImageComparison& c) {
    return {{"mae", c.mae}, {"psnr_db", finiteOrNull(c.psnr)}, {"ssim", c.ssim}};
}

}  // namespace raycache
