#pragma once
// Figures 5.1, 5.4, 5.5: what CCT's nearest-neighbour cube faces cost in
// image quality. The room scene's mirror ball seen from far and close up,
// cached at 128², 256² and 512² faces, against the uncached render: MAE,
// PSNR, SSIM and a difference heat map for each.
#include <memory>

#include "bench/Experiment.h"

namespace raycache {

std::unique_ptr<Experiment> makeQualityExperiment();

}  // namespace raycache
