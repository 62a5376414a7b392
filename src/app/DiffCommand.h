#pragma once
// `raycache diff a b [--heatmap out.png]`: how different two images are, as
// the experiments measure it (MAE, PSNR, SSIM on the displayed images), with
// an optional heat map of the per-pixel difference.
#include <iosfwd>
#include <string>

namespace raycache {

struct DiffCommandOptions {
    std::string first;
    std::string second;
    std::string heatmap;      // image to write; empty = none
    double heatmapMax = 1.0;  // difference drawn as full red
};

// Prints the metrics to `out`. Throws InputError for unreadable or
// mismatched images and a bad heat map path or scale (checked before
// anything is written), RuntimeError if writing the heat map fails.
void runDiffCommand(const DiffCommandOptions& options, std::ostream& out);

}  // namespace raycache
