#include "app/DiffCommand.h"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "app/OutputDirectory.h"
#include "core/Errors.h"
#include "metrics/Heatmap.h"
#include "metrics/ImageMetrics.h"
#include "metrics/Ssim.h"
#include "render/ImageWriter.h"
#include "scene/ImageLoader.h"
#include "session/FrameReport.h"

namespace raycache {

void runDiffCommand(const DiffCommandOptions& options, std::ostream& out) {
    if (!options.heatmap.empty() && !isSupportedImageExtension(options.heatmap))
        checkWritableImagePath(options.heatmap);  // reports the unsupported format before any work
    if (!(std::isfinite(options.heatmapMax) && options.heatmapMax > 0.0 && options.heatmapMax <= 1.0))
        throw InputError("--heatmap-max must be in (0, 1]");
    const Image a = loadImageFile(options.first);
    const Image b = loadImageFile(options.second);
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError("images differ in size: " + options.first + " is " + std::to_string(a.width()) + "x" +
                         std::to_string(a.height()) + ", " + options.second + " is " + std::to_string(b.width()) + "x" +
                         std::to_string(b.height()));
    if (!options.heatmap.empty()) createParentDirectories(options.heatmap);

    const double mae = meanAbsoluteError(a, b);
    const double peak = psnr(a, b);
    const double structural = ssim(a, b);
    const std::vector<float> diff = pixelDifferences(a, b);
    const float maxDiff = diff.empty() ? 0.0f : *std::max_element(diff.begin(), diff.end());
    // One 8-bit display step: smaller differences cannot show in a PNG.
    const auto differing = std::count_if(diff.begin(), diff.end(), [](float d) { return d > 0.5f / 255.0f; });

    out << options.first << " vs " << options.second << ": " << a.width() << "x" << a.height() << "\n";
    out << "MAE   " << formatFixed(mae, 6) << "   (mean |difference| per channel, displayed sRGB, 0..1)\n";
    out << "PSNR  " << (std::isinf(peak) ? std::string("inf (identical)") : formatFixed(peak, 2) + " dB") << "\n";
    out << "SSIM  " << formatFixed(structural, 5) << "\n";
    out << "max pixel difference " << formatFixed(maxDiff, 4) << ", pixels differing by more than half an 8-bit step "
        << formatFixed(
               100.0 * static_cast<double>(differing) / static_cast<double>(std::max<std::size_t>(1, diff.size())), 2)
        << "%\n";
    if (!options.heatmap.empty()) {
        writeImage(renderHeatmap(a, b, {options.heatmapMax}), options.heatmap);
        out << "wrote " << options.heatmap << " (blue = same, red = difference " << formatFixed(options.heatmapMax, 2)
            << " or more)\n";
    }
}

}  // namespace raycache
