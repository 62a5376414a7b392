#pragma once
// Figure 5.9: how fast caching cubes fill. One caching sphere in front of
// the camera (behind-0's main sphere), the camera moved around it in 9 steps
// of 10/3 degrees; the share of invalid texels before each frame, for face
// resolutions 128², 256² and 512².
#include <memory>

#include "bench/Experiment.h"

namespace raycache {

std::unique_ptr<Experiment> makeFillRateExperiment();

}  // namespace raycache
