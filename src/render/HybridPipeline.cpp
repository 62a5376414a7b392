#include "render/HybridPipeline.h"

#include <chrono>

#include "raster/GBufferRasterizer.h"

namespace raycache {

HybridPipeline::HybridPipeline(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                               const Parallel& parallel, RayCache* cache,
                               std::unique_ptr<GBufferRasterizer> rasterizer, std::string fallbackReason)
    : settings_(settings), rasterizer_(std::move(rasterizer)), fallbackReason_(std::move(fallbackReason)),
      packets_(scene, tracer, parallel, settings.tileSize), deferred_(scene, tracer, settings, parallel, cache) {}

HybridPipeline::~HybridPipeline() = default;

FrameStats HybridPipeline::render(const Camera& camera, Image& film) {
    FrameStats stats;
    PhaseTimes& phases = stats.phases.emplace();
    GBufferView gbuffer;
    if (rasterizer_) {
        RasterTimes times;
        gbuffer = rasterizer_->rasterize(camera, settings_.width, settings_.height, times);
        phases.raster = times.raster;
        phases.readback = times.readback;
    } else {
        const auto start = std::chrono::steady_clock::now();
        stats.rays.primary += packets_.fill(camera, settings_.width, settings_.height, storage_);
        gbuffer = storage_.view();
        phases.raster = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    deferred_.shade(camera, gbuffer, film, stats, &cacheLevels_);
    return stats;
}

void HybridPipeline::sceneChanged(const SceneChanges& changes) {
    if (rasterizer_ && !changes.objects.empty()) rasterizer_->sceneChanged(changes.objects);
}

std::string HybridPipeline::description() const {
    if (rasterizer_) return "pipeline: hybrid, G-buffer by OpenGL (" + rasterizer_->description() + ")";
    return "pipeline: hybrid, G-buffer by primary-ray packets (" + fallbackReason_ + ")";
}

}  // namespace raycache
