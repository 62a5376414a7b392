#include "session/PipelineFactory.h"

#include <optional>
#include <string>

#include "core/Errors.h"
#include "raster/GBufferRasterizer.h"
#include "render/FilteredFilm.h"
#include "render/FrameRenderer.h"
#include "render/PixelSamples.h"
#include "render/HybridPipeline.h"
#include "rendercache/RenderCachePipeline.h"

namespace raycache {

namespace {

class RayPipeline final : public FramePipeline {
public:
    RayPipeline(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                const Parallel& parallel, RayCache* cache, const ProcessGroup* group)
        : renderer_(scene, tracer, settings, parallel, cache, group), parallel_(parallel),
          samples_(settings.samplesPerPixel), width_(settings.width), height_(settings.height), recordsLevels_(settings.recordCacheLevels) {}
    FrameStats render(const Camera& camera, Image& film) override {
        if (samples_.count() == 1) return renderer_.render(camera, film, &cacheLevels_);
        return renderSamples(camera, film);
    }
    FrameStats renderSample(const Camera& camera, Image& layer, const PixelSamples& samples, int sample) override {
        return renderer_.render(camera, layer, nullptr, &samples, sample);
    }
    std::string description() const override { return "pipeline: ray (primary rays as packets)"; }
    const CacheLevelImage* cacheLevels() const override { return recordsLevels_ ? &cacheLevels_ : nullptr; }

private:
    // --spp N: N sample layers, each rendered as a frame (caches keyed as
    // ever: a jittered ray asks its cube like any other), gathered through
    // the pixel filter. The stats count every layer's rays; the cache
    // figures are the last layer's.
    FrameStats renderSamples(const Camera& camera, Image& film) {
        FilteredFilm filtered(width_, height_);
        FrameStats stats;
        RayCounts rays;
        std::optional<StageTimes> stages;
        for (int s = 0; s < samples_.count(); ++s) {
            stats = renderSample(camera, layer_, samples_, s);
            rays += stats.rays;
            if (stats.stages && stages) *stages += *stats.stages;
            else if (stats.stages) stages = stats.stages;
            filtered.addLayer(layer_, samples_, s, parallel_);
        }
        filtered.resolve(film, parallel_);
        stats.rays = rays;
        stats.stages = stages;
        return stats;
    }

    FrameRenderer renderer_;
    const Parallel& parallel_;
    PixelSamples samples_;
    int width_, height_;
    Image layer_;
    bool recordsLevels_;
    CacheLevelImage cacheLevels_;  // the last frame's, when RenderSettings::recordCacheLevels
};

}  // namespace

std::unique_ptr<FramePipeline> makeFramePipeline(const Scene& scene, const TraceScene& tracer,
                                                 const RenderSettings& settings, const Parallel& parallel,
                                                 RayCache* cache, const ProcessGroup* group) {
    if (settings.pipeline == PipelineKind::Ray)
        return std::make_unique<RayPipeline>(scene, tracer, settings, parallel, cache, group);
    // The hybrid pipeline's G-buffer pass and the Render Cache's sample
    // reprojection are whole-frame passes that do not split by tile.
    if (settings.samplesPerPixel != 1)
        throw InputError(std::string("--spp ") + std::to_string(settings.samplesPerPixel) +
                         " needs --pipeline ray (the " + pipelineKindName(settings.pipeline) +
                         " pipeline renders one ray per pixel)");
    if (group && group->size() > 1)
        throw InputError(std::string("--pipeline ") + pipelineKindName(settings.pipeline) +
                         " does not share a frame's tiles among MPI processes; use --pipeline ray (or, with caches "
                         "off and several frames, the processes render whole frames: docs/cluster.md)");
    if (settings.pipeline == PipelineKind::RenderCache)
        return std::make_unique<RenderCachePipeline>(scene, tracer, settings, parallel, cache);
    std::unique_ptr<GBufferRasterizer> rasterizer;
    std::string reason = "asked for with --gbuffer packets";
    if (settings.gbuffer != GBufferSource::Packets) {
        std::string whyNot;
        rasterizer = GBufferRasterizer::create(scene, whyNot);
        if (!rasterizer) {
            while (!whyNot.empty() && (whyNot.back() == ' ' || whyNot.back() == ';')) whyNot.pop_back();
            if (settings.gbuffer == GBufferSource::OpenGl)
                throw RuntimeError("no OpenGL 4.5 core context for the G-buffer: " + whyNot);
            reason = "no OpenGL 4.5 core context: " + whyNot;
        }
    }
    return std::make_unique<HybridPipeline>(scene, tracer, settings, parallel, cache, std::move(rasterizer),
                                            std::move(reason));
}

}  // namespace raycache
