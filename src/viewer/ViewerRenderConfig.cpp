#include "viewer/ViewerRenderConfig.h"

#include "cache/RayCache.h"
#include "core/Errors.h"
#include "viewer/PipelineChoice.h"
#include "viewer/TechniqueChoice.h"

namespace raycache {

RenderSettings applyViewerRenderConfig(const RenderSettings& base, const ViewerRenderConfig& config) {
    RenderSettings s = base;
    s.maxDepth = config.maxDepth;
    s.cache.techniqueOverride = kTechniqueChoices.at(static_cast<std::size_t>(config.technique)).technique;
    if (config.cacheResolution) s.cache.resolutionOverride = config.cacheResolution;
    if (config.cdctStep) s.cache.cdctStepOverride = config.cdctStep;
    if (config.cdctEpsilon) s.cache.cdctEpsilonOverride = config.cdctEpsilon;
    kPipelineChoices.at(static_cast<std::size_t>(config.pipeline)).apply(s);
    s.trace.accelerator = config.accelerator;
    return s;
}

std::string viewerRenderConfigError(const Scene& scene, const RenderSettings& base, const ViewerRenderConfig& config) {
    if (config.technique < 0 || static_cast<std::size_t>(config.technique) >= kTechniqueChoices.size())
        return "unknown technique";
    if (config.pipeline < 0 || static_cast<std::size_t>(config.pipeline) >= kPipelineChoices.size())
        return "unknown pipeline";
    if (config.maxDepth < 1 || config.maxDepth > 64) return "maximum depth must be between 1 and 64";
    try {
        RayCache::validate(scene, applyViewerRenderConfig(base, config).cache);
    } catch (const InputError& e) {
        return e.what();
    }
    return {};
}

}  // namespace raycache
