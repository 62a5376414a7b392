#pragma once
// The Render Cache along moving-camera paths: on room, behind-32
// and glass, each frame rendered in full (the ray pipeline: reference image
// and speed baseline), by the plain Render Cache (reprojected colour) and by
// the Render Cache with re-evaluated reflections, in turn. Frame time split
// into reconstruction and sample generation, quality per frame against the
// full render (PSNR, SSIM, mirror pixels, heat maps), the share of fresh
// pixels, the documents' GPU figures and our goals beside them.
#include <memory>

#include "bench/Experiment.h"

namespace raycache {

std::unique_ptr<Experiment> makeRenderCacheExperiment();

}  // namespace raycache
