#pragma once
// Dynamic scenes (docs/dynamic-scenes.md): every built-in animated scene
// played frame by frame, uncached and with CCT side by side (interleaved
// frame by frame): frame times, the scene update's share, the caches' hit
// rate and texels dropped, PSNR of the CCT frame against the uncached one;
// and, at a smaller size, the invalidation oracle's counts (stale and
// needless drops against the texels that really changed).
#include <memory>

#include "bench/Experiment.h"

namespace raycache {

std::unique_ptr<Experiment> makeDynamicExperiment();

}  // namespace raycache
