#pragma once
// The Render Cache as a pipeline (Walter et al. 1999; Zhu, Wang and Luebke 2005; `--pipeline render-cache`):
// frames are made from the point samples of earlier frames, reprojected to
// the new camera, plus a budget of new camera rays traced where the request
// map asks (holes, old samples, and where the predicted next camera will
// open holes). Holes left are filled by the 3x3 filter and the 7x7
// prefilter. New samples come from the tile kernel with the frame's caching
// technique (none, CCT, CDCT). Samples on mirrors, glass and glossy
// surfaces keep their view-independent light and, with
// ReprojectedReflections::Reshade, have highlights and reflected/refracted
// colour evaluated again from the new eye (the caching cubes answer those
// rays where they can).
//
// The first frame, and any frame with more than
// RenderCacheSettings::refreshAllHoleShare of its pixels in holes, traces
// every pixel. With a fixed budget images do not depend on the thread count.
//
// The asynchronous mode (rendercache/AsyncRenderCache.h) splits a frame in
// two halves that run on two threads: reconstruct() (reprojection, maps,
// reshading, hole filling: the image for the newest camera, and a request
// for new samples) and traceSamples() (the requested camera rays).
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "render/FramePipeline.h"
#include "render/TileKernel.h"
#include "rendercache/PointImage.h"
#include "rendercache/RenderCacheOverlays.h"
#include "rendercache/Reprojection.h"
#include "rendercache/SampleBatch.h"
#include "rendercache/SamplePool.h"
#include "rendercache/SampleRequest.h"

namespace raycache {

class CacheFrame;

class RenderCachePipeline final : public FramePipeline {
public:
    // Throws InputError for invalid RenderSettings::renderCache values.
    RenderCachePipeline(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                        const Parallel& parallel, RayCache* cache);

    FrameStats render(const Camera& camera, Image& film) override;

    // The asynchronous mode's display half: a frame that traces no camera
    // ray. First merges `batches` into the pool (samples traced through the
    // camera of the last frame go to their pixels' slots, as render() keeps
    // its new samples; the others wait in overflow slots, as predicted
    // samples do, and are reprojected with the rest; returns how many in
    // `merged`), ages the samples by `ageStep`, then reprojects, reshades
    // and fills holes as render() does. With `request`, fills it with what
    // this frame's maps ask for (`budget` rays, 0: the settings' budget);
    // without, builds no request map (one is still being traced). Scenes
    // that move are not for this mode: meshes are not refreshed.
    FrameStats reconstruct(const Camera& camera, Image& film, std::span<const SampleBatch> batches, int ageStep,
                           int budget, SampleRequest* request, std::int64_t& merged);
    // The asynchronous mode's tracer half: traces the rays through `pixels`
    // of `camera` on `parallel`'s threads, with `scratch` (resized to them),
    // into `out`; returns the rays traced. May run on another thread while
    // reconstruct() runs: the two share the scene, the tracer and the kernel
    // (read only) and the caches, whose frames they take one at a time.
    RayCounts traceSamples(const Camera& camera, std::span<const PixelCoord> pixels, const Parallel& parallel,
                           std::vector<TileScratch>& scratch, std::span<PrimarySample> out);
    // Held by reconstruct() and traceSamples() while they use the caches:
    // whoever else reads the caches while they may run holds it too.
    std::mutex& cacheMutex() { return cacheMutex_; }
    std::string description() const override;
    const RenderCacheOverlays* renderCacheOverlays() const override { return &overlays_; }
    // RenderCacheSettings::reshadeInterval from the next frame on (the
    // asynchronous display's budget, rendercache/ReshadeBudget.h).
    void setReshadeInterval(int interval) { settings_.renderCache.reshadeInterval = interval; }
    int reshadeInterval() const { return settings_.renderCache.reshadeInterval; }

    // Samples follow their object's translation (they are kept relative to
    // its origin); on an object that turns, scales or deforms they would
    // land in the wrong place, so a change of such an object drops them.
    void sceneChanged(const SceneChanges& changes) override;

private:
    struct AsyncFrame {
        std::span<const SampleBatch> batches;
        int ageStep = 1;
        int budget = 0;
        SampleRequest* request = nullptr;
        std::int64_t merged = 0;
    };
    // What a frame carries from pass to pass (RenderCacheFrameContext.h).
    struct FrameContext;

    // render() with `async` null; reconstruct() otherwise: the passes below, in order.
    FrameStats frame(const Camera& camera, Image& film, AsyncFrame* async);
    // The pool sized for the image and its margin (a new size drops every sample).
    void sizePool(std::size_t imageSlots, int pixels);
    // Ages, evicts and reprojects the samples to the frame's camera (and
    // through the predicted next camera); the pool then holds each pixel's
    // winner at its slot (ReprojectionPass.cpp).
    void reprojectSamples(FrameContext& f);
    // Per pixel: a hole, a culled sample or a reprojected one; its priority;
    // a textured sample's albedo fetched again at the pixel's centre
    // (PixelClassificationPass.cpp).
    void classifyPixels(FrameContext& f);
    // The frame's budget and its request map (RequestPass.cpp).
    void requestSamples(FrameContext& f);
    // render(): traces the requested pixels and keeps their samples;
    // reconstruct(): hands the request over instead (NewSamplesPass.cpp).
    void traceNewSamples(FrameContext& f);
    // Where the predicted next camera will find holes, and rays through it
    // there (PredictionPass.cpp).
    void predictNextHoles(FrameContext& f);
    // Highlights, reflections and refractions of reprojected samples from the
    // new eye, then the end of the caches' frame (ReshadingPass.cpp).
    void reshadeSamples(FrameContext& f);
    // The film: samples where there are, the edge-aware fills in the holes,
    // texture at the filled holes' centres, the environment where nothing
    // reaches (ImagePass.cpp).
    void makeImage(FrameContext& f);
    // The counted bytes, the adaptive budget for the next frame, and the stats.
    FrameStats endFrame(FrameContext& f);
    // Puts traced samples into the pool (see reconstruct()); returns how many.
    std::int64_t merge(std::span<const SampleBatch> batches);
    // Traces the camera rays through `pixels` in fixed chunks (the chunk
    // index, offset by `firstKey`, orders the cache stores); returns the
    // next unused key.
    std::uint64_t trace(const Camera& camera, const std::vector<PixelCoord>& pixels, std::uint64_t firstKey,
                        CacheFrame& cacheFrame, std::vector<PrimarySample>& out);
    // Stores sample `traced` of the ray through `pixel` of `camera` in `slot`.
    void keep(std::size_t slot, const PrimarySample& traced, const CameraRays& rays, const PixelCoord& pixel);
    int chooseBudget(int pixels) const;

    const Scene& scene_;
    RenderSettings settings_;
    const Parallel& parallel_;
    RayCache* cache_;
    TileKernel kernel_;
    std::vector<TileScratch> scratch_;

    // The samples, in pixel order, and the buffer reprojection copies them
    // into (then the two swap), as the GPU Render Cache does.
    SamplePool pool_, spare_;
    ReprojectionScratch reprojectionScratch_;
    // Per pixel slot: the pixel its sample lands in through the predicted
    // camera (imagePixelThrough), on frames that predict.
    std::vector<std::int32_t> nextPixel_;
    // Per object: animated by more than a translation (rotation or scale
    // keys, or a deformation).
    std::vector<unsigned char> movesNonRigidly_;
    PointImage image_;
    RenderCacheOverlays overlays_;
    RequestMap predictedRequests_;
    // Buffers reused from frame to frame: fresh memory costs page faults.
    std::vector<float> priority_;
    std::vector<std::int32_t> fillSource_;  // per pixel: the sample a filled hole took its surface from
    std::vector<unsigned char> bytes_;  // each step's own per-pixel flags, one step at a time
    std::vector<PrimarySample> traced_;
    std::vector<ReshadeRequest> reshade_;
    std::vector<std::uint32_t> reshadeSlots_;
    // Per row, from index 1: the reprojected samples that depend on the eye,
    // counted by classifyPixels (less those traceNewSamples replaces), so
    // that reshading places each row's requests without a walk of its own.
    std::vector<std::size_t> reshadeRowStart_;
    // Per row, pixelStateWords(width) words: the reprojected samples
    // classifyPixels chose to reshade, as bits (rendercache/PixelStateBits.h's
    // layout), so that reshading visits them alone, not every pixel.
    std::vector<std::uint64_t> reshadeBits_;
    std::vector<Rgb> reshadeColors_;
    std::optional<Camera> previousCamera_;
    std::uint32_t movingFrames_ = 0;  // frames whose camera moved: the reshading pattern's shift
    std::uint64_t frame_ = 0;
    double adaptiveBudget_ = 0.0;  // rays, when a target frame time is set
    // Asynchronous mode: the caches take one frame at a time (a CacheFrame
    // begins and ends a cache frame), the tracer's or the display's.
    std::mutex cacheMutex_;
};

}  // namespace raycache
