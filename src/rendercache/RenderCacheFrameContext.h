#pragma once
// What one frame of the Render Cache pipeline carries from pass to pass
// (RenderCachePipeline::frame, whose passes each live in a file named for
// them: ReprojectionPass, PixelClassificationPass, RequestPass,
// NewSamplesPass, PredictionPass, ReshadingPass, ImagePass). Private to the
// pipeline.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "core/Image.h"
#include "render/CacheFrame.h"
#include "render/FrameStats.h"
#include "rendercache/HoleFilling.h"
#include "rendercache/ReconstructionBytes.h"
#include "rendercache/RenderCachePipeline.h"
#include "rendercache/Reprojection.h"
#include "rendercache/ReshadeSelection.h"
#include "rendercache/ScreenProjection.h"

namespace raycache {

struct RenderCachePipeline::FrameContext {
    FrameContext(const Camera& frameCamera, Image& frameFilm, AsyncFrame* asyncFrame, const RenderSettings& settings,
                 int frameMargin, std::size_t slots, bool cameraMoved, std::uint32_t movingFrames,
                 const std::optional<Camera>& previousCamera, const Scene& scene);

    // What the frame is asked for.
    const Camera& camera;
    Image& film;
    AsyncFrame* async;  // null: render(), which also traces; else reconstruct()
    const RenderCacheSettings& rc;
    const int width, height, pixels;
    const int margin;              // pool slots past each edge of the image
    const std::size_t imageSlots;  // pool slots of the image and its margin
    const bool moved;              // the camera differs from the last frame's
    const ReshadeSelection reshading;  // which reprojected samples reshading takes
    // The asynchronous mode asks for samples only when the last request is
    // traced and merged; meanwhile it makes no request map.
    const bool wantsRequests;
    // Predictive sampling: samples are projected through the extrapolated
    // next camera too, in reprojection's pass.
    const bool predicts;
    const Camera next;
    const ScreenProjection projection, nextProjection;
    const std::vector<Vec3> origins;  // every object's, for the samples' positions
    const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

    // What the passes found.
    RenderCacheStats stats;
    ReconstructionCounts touched;  // for the counted bytes the passes move
    ReprojectionCounts reprojected;
    std::int64_t newSamples = 0;  // taking a slot no sample held: in a hole, or predicted
    std::int64_t holes = 0;       // holes and culled samples
    int budget = 0;               // rays this frame's maps ask for
    int predictedBudget = 0;      // of those, through the predicted camera

    // The caches' frame: this frame's camera rays and reshading look up and
    // store through it. The asynchronous mode's display takes it only after
    // the tracer's has ended (the lock).
    std::unique_lock<std::mutex> cacheLock;
    std::optional<CacheFrame> cacheFrame;
    std::uint64_t key = 0;  // orders the cache's stores: the next chunk's
    FrameStats frameStats;
    FillCounts filled;
};

}  // namespace raycache
