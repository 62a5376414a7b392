#pragma once
// A deliberately plain Whitted loop straight on Embree: one rtcIntersect1 per
// ray, Lambert shading, one rtcOccluded1 per light, mirror reflection only.
// It is the yardstick the real renderer is benchmarked against (same scene,
// same rays), not a renderer to use.
#include <cstdint>
#include <memory>

#include "core/Image.h"
#include "core/Parallel.h"
#include "scene/Scene.h"
#include "trace/TraceScene.h"

namespace raycache {

class BaselineWhitted {
public:
    // With `shared`, traces raycache's own acceleration structure; without it,
    // builds the plain one (Embree's built-in sphere primitives), which is what
    // a straightforward Embree program would do.
    BaselineWhitted(const Scene& scene, const TraceScene* shared);
    ~BaselineWhitted();
    BaselineWhitted(const BaselineWhitted&) = delete;
    BaselineWhitted& operator=(const BaselineWhitted&) = delete;

    // Renders scene.camera at film's size with paths of at most maxDepth rays;
    // returns the number of rays traced.
    std::uint64_t render(const Parallel& parallel, int maxDepth, Image& film) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace raycache
