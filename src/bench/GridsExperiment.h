#pragma once
// `raycache bench grids` (docs/grids.md): per model and frame,
// build and trace time of primary rays and of the shadow rays of their hits,
// the grids against Embree rebuilt every frame at its fastest (LOW) and its
// default (MEDIUM) build quality with 16-wide coherent packets; static
// meshes from 10k to 1M triangles and the animated built-in scenes; the
// document's Table 1 beside ours; a plot of time against triangle count; and
// the grids' agreement with Embree (ties and edge grazes counted).
#include <memory>

#include "bench/Experiment.h"

namespace raycache {

std::unique_ptr<Experiment> makeGridsExperiment();

}  // namespace raycache
