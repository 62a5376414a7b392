#pragma once
// `raycache bench where-caching-pays` (docs/caching.md "When caching pays"):
// for the built-in scenes and those made of real meshes, the measured
// speed-up of CCT and CDCT over uncached rendering, with caches filled (still
// camera) and along the scene's camera path and animation from empty caches,
// beside what bench/CachingPayModel.h predicts from measured parts of the
// frames (the ideal cache's frame, the lookups' cost, the hit rate), the
// model's error, and a plot of speed-up against the cacheable share.
#include <memory>

#include "bench/Experiment.h"

namespace raycache {

std::unique_ptr<Experiment> makeWhereCachingPaysExperiment();

}  // namespace raycache
