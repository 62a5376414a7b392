#pragma once
// A deliberately plain Whitted loop straight on Embree: one rtcIntersect1 per
// ray, Lambert shading, one rtcOccluded1 per light, mirror reflection only.
// It is the yardstick the real renderer is benchmarked against (same scene,
// same rays), not a renderer to use.
#include <cstdint>

#include "core/Image.h"
#include "core/Parallel.h"
#include "scene/Scene.h"
#include "trace/TraceScene.h"

namespace raycache {

// Renders scene.camera at film's size with paths of at most maxDepth rays;
// returns the number of rays traced.
std::uint64_t renderBaselineWhitted(const Scene& scene, const TraceScene& tracer, const Parallel& parallel,
                                    int maxDepth, Image& film);

}  // namespace raycache
