#pragma once
// How a scene file asks to be rendered (its "pipeline" and "renderCache"
// keys, docs/scene-format.md): defaults that command-line options override.
// Plain values, checked when the file is read.
#include <optional>
#include <string>

namespace raycache {

struct SceneRenderDefaults {
    std::optional<std::string> pipeline;  // ray | hybrid | render-cache
    // The Render Cache's options (rendercache/RenderCacheSettings.h).
    std::optional<float> rcBudget, rcTargetMs, rcAlpha, rcPredict;
    std::optional<int> rcMaxAge;
    std::optional<std::string> rcReflections;  // reshade | reproject
};

}  // namespace raycache
