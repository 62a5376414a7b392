#include "session/PipelineFactory.h"

#include "core/Errors.h"
#include "raster/GBufferRasterizer.h"
#include "render/FrameRenderer.h"
#include "render/HybridPipeline.h"
#include "rendercache/RenderCachePipeline.h"

namespace raycache {

namespace {

class RayPipeline final : public FramePipeline {
public:
    RayPipeline(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                const Parallel& parallel, RayCache* cache, const ProcessGroup* group)
        : renderer_(scene, tracer, settings, parallel, cache, group), recordsLevels_(settings.recordCacheLevels) {}
    FrameStats render(const Camera& camera, Image& film) override {
        return renderer_.render(camera, film, &cacheLevels_);
    }
    std::string description() const override { return "pipeline: ray (primary rays as packets)"; }
    const CacheLevelImage* cacheLevels() const override { return recordsLevels_ ? &cacheLevels_ : nullptr; }

private:
    FrameRenderer renderer_;
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
