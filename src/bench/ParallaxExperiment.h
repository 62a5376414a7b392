#pragma once
// Figure 3.5: parallax. CCT stores what a ray saw by direction only, as if
// everything were infinitely far; CDCT also stores depth. Along the parallax
// scene's camera move (two facing mirror spheres, a near box, a far wall),
// each cached render is compared frame by frame with the uncached one.
#include <memory>

#include "bench/Experiment.h"

namespace raycache {

std::unique_ptr<Experiment> makeParallaxExperiment();

}  // namespace raycache
