#pragma once
// The rendering parameters the viewer's panel edits. Changing any of them
// rebuilds the caches (their contents depend on all of them).
#include <optional>
#include <string>

#include "render/RenderSettings.h"

namespace raycache {

struct ViewerRenderConfig {
    int technique = 0;                   // index into kTechniqueChoices
    int pipeline = 0;                    // index into kPipelineChoices
    Accelerator accelerator = Accelerator::Embree;  // primary and first shadow rays (docs/grids.md)
    std::optional<int> cacheResolution;  // empty: every material's own
    std::optional<float> cdctStep;       // empty: every material's own
    std::optional<float> cdctEpsilon;
    int maxDepth = 6;

    bool operator==(const ViewerRenderConfig&) const = default;
};

// `base` (size, threads, min weight, cache overrides from the command line)
// with the config's choices applied. The config must be valid (see
// validateViewerRenderConfig).
RenderSettings applyViewerRenderConfig(const RenderSettings& base, const ViewerRenderConfig& config);

// Empty if `config` can be rendered for `scene`; otherwise the InputError's
// message, for the panel to show (the previous config stays in use).
std::string viewerRenderConfigError(const Scene& scene, const RenderSettings& base, const ViewerRenderConfig& config);

}  // namespace raycache
