#pragma once
// How a scene file asks to be rendered (its "pipeline" and "renderCache"
// keys, docs/scene-format.md): defaults that command-line options override.
// Plain values, checked when the file is read.
#include <cstdint>
#include <optional>

#include "core/ViewTransform.h"
#include "scene/Accelerator.h"
#include "scene/PipelineKind.h"
#include "scene/ReprojectedReflections.h"

namespace raycache {

// The Render Cache's options (render/RenderCacheSettings.h) that a
// scene file or the command line sets; those left unset keep their value.
struct RenderCacheOverrides {
    std::optional<float> budget, targetFrameMs, alpha, predictShare, margin, depthCullThreshold;
    std::optional<int> maxAge, requestTileSize, reshadeInterval;
    std::optional<std::uint64_t> seed;
    std::optional<ReprojectedReflections> reflections;
    std::optional<bool> textureRefetch;      // RenderCacheSettings::textureRefetch (command line only)
};

struct SceneRenderDefaults {
    std::optional<PipelineKind> pipeline;
    std::optional<Accelerator> accel;      // docs/grids.md
    std::optional<double> cacheBudgetMiB;  // the caching cubes' memory budget (cache/CubeBudget.h)
    std::optional<float> exposure;             // stops (core/DisplayTransform.h)
    std::optional<ViewTransform> viewTransform;
    RenderCacheOverrides renderCache;
};

}  // namespace raycache
