#pragma once
// The hybrid raster + ray tracing pipeline (Ruff, Clua and Fernandes 2013): a G-buffer (OpenGL, or
// primary-ray packets), then the deferred passes (render/DeferredShading.h).
#include <memory>
#include <string>

#include "raster/GBuffer.h"
#include "render/DeferredShading.h"
#include "render/FramePipeline.h"
#include "render/PacketGBuffer.h"

namespace raycache {

class GBufferRasterizer;

class HybridPipeline final : public FramePipeline {
public:
    // `rasterizer` null: the G-buffer comes from primary-ray packets, and
    // `fallbackReason` says why (for the description).
    HybridPipeline(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                   const Parallel& parallel, RayCache* cache, std::unique_ptr<GBufferRasterizer> rasterizer,
                   std::string fallbackReason);
    ~HybridPipeline() override;

    FrameStats render(const Camera& camera, Image& film) override;
    std::string description() const override;
    bool usesOpenGl() const { return rasterizer_ != nullptr; }
    void sceneChanged(const SceneChanges& changes) override;
    const CacheLevelImage* cacheLevels() const override {
        return settings_.recordCacheLevels ? &cacheLevels_ : nullptr;
    }

private:
    RenderSettings settings_;
    std::unique_ptr<GBufferRasterizer> rasterizer_;
    std::string fallbackReason_;
    PacketGBuffer packets_;
    GBufferStorage storage_;  // the packet G-buffer
    DeferredShading deferred_;
    CacheLevelImage cacheLevels_;  // the last frame's, when RenderSettings::recordCacheLevels
};

}  // namespace raycache
