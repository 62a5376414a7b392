#include "viewer/AutoPipelineRule.h"

namespace raycache {

const char* shownPipelineName(ShownPipeline shown) {
    return shown == ShownPipeline::FullFrame ? "full frames" : "Render Cache";
}

void AutoPipelineRule::observe(ShownPipeline shown, double renderMs, std::int64_t pixels) {
    if (pixels <= 0 || !(renderMs >= 0.0)) return;
    const double perPixel = renderMs / static_cast<double>(pixels);
    double& estimate = shown == ShownPipeline::FullFrame ? fullMsPerPixel_ : renderCacheMsPerPixel_;
    estimate = estimate < 0.0 ? perPixel : (1.0 - kNewWeight) * estimate + kNewWeight * perPixel;
}

double AutoPipelineRule::estimateMs(ShownPipeline way, std::int64_t pixels) const {
    const double perPixel = way == ShownPipeline::FullFrame ? fullMsPerPixel_ : renderCacheMsPerPixel_;
    return perPixel < 0.0 ? -1.0 : perPixel * static_cast<double>(pixels);
}

ShownPipeline AutoPipelineRule::choose(bool moving, bool renderCacheAllowed, std::int64_t fullPixels,
                                       std::int64_t renderCachePixels) {
    current_ = [&] {
        // Still: the full render itself, exactly.
        if (!moving || !renderCacheAllowed) return ShownPipeline::FullFrame;
        const double full = estimateMs(ShownPipeline::FullFrame, fullPixels);
        // No full frame measured yet, or full frames keep the rate.
        if (full < 0.0 || full <= targetMs_) return ShownPipeline::FullFrame;
        const double renderCache = estimateMs(ShownPipeline::RenderCache, renderCachePixels);
        // Never measured: the only way to learn what it costs is to show it.
        if (renderCache < 0.0) return ShownPipeline::RenderCache;
        const double share = current_ == ShownPipeline::RenderCache ? 1.0 : kSwitchShare;
        return renderCache < share * full ? ShownPipeline::RenderCache : ShownPipeline::FullFrame;
    }();
    return current_;
}

}  // namespace raycache
