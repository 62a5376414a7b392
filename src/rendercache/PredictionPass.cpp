// RenderCachePipeline's predictive sampling (enhanced Render Cache): rays
// through the extrapolated next camera where it will find holes. Their
// samples have no pixel yet: they wait in the pool's overflow slots for the
// next frame's reprojection.
#include <algorithm>
#include <atomic>

#include "core/Elapsed.h"
#include "render/CameraRays.h"
#include "rendercache/RenderCacheFrameContext.h"
#include "rendercache/RequestMap.h"

namespace raycache {

void RenderCachePipeline::predictNextHoles(FrameContext& f) {
    if (f.predictedBudget <= 0) return;
    const int width = f.width, height = f.height;
    auto start = std::chrono::steady_clock::now();
    // Where the samples land through the next camera was found by
    // reproject() (fresh samples: when kept); every sample is in a pixel
    // slot until the predicted ones are kept below.
    std::vector<unsigned char>& covered = bytes_;
    covered.assign(static_cast<std::size_t>(f.pixels), 0);
    const std::size_t n = pool_.pixelSlots;
    constexpr std::size_t kChunk = 16384;
    parallel_.forEachIndex(static_cast<int>((n + kChunk - 1) / kChunk), [&](int chunk, int) {
        const std::size_t end = std::min(n, (static_cast<std::size_t>(chunk) + 1) * kChunk);
        for (std::size_t slot = static_cast<std::size_t>(chunk) * kChunk; slot < end; ++slot)
            if (const std::int32_t pixel = nextPixel_[slot]; pixel >= 0)
                std::atomic_ref<unsigned char>(covered[static_cast<std::size_t>(pixel)])
                    .store(1, std::memory_order_relaxed);
    });
    std::vector<float>& priority = priority_;
    parallel_.forEachIndex(height, [&](int y, int) {
        for (auto i = static_cast<std::size_t>(y * width); i < static_cast<std::size_t>((y + 1) * width); ++i)
            priority[i] = covered[i] ? 0.0f : 1.0f;
    });
    buildRequestMap(priority, width, height, f.rc.requestTileSize, 1.0f, f.predictedBudget, f.rc.seed ^ 0x5eed, frame_,
                    predictedRequests_, parallel_);
    const std::size_t offered = predictedRequests_.pixels.size();
    // Only holes: a tile without any gets no ray even if rounding offered one.
    std::erase_if(predictedRequests_.pixels,
                  [&](const PixelCoord& p) { return covered[static_cast<std::size_t>(p.y * width + p.x)] != 0; });
    f.stats.mapsMs += millisecondsSince(start);
    f.touched.predictionMap = true;
    f.touched.predictedOffered = static_cast<std::int64_t>(offered);
    f.touched.predictedKept = static_cast<std::int64_t>(predictedRequests_.pixels.size());
    f.touched.pixelsInPredictedTiles = pixelsInTilesWithRequests(predictedRequests_, width, height);
    start = std::chrono::steady_clock::now();
    if (f.async) {
        f.async->request->nextCamera = f.next;
        f.async->request->predicted = predictedRequests_.pixels;
    } else {
        std::vector<PrimarySample>& traced = traced_;
        f.key = trace(f.next, predictedRequests_.pixels, f.key, *f.cacheFrame, traced);
        const CameraRays rays(f.next, width, height);
        for (std::size_t i = 0; i < traced.size(); ++i)
            keep(pool_.takeOverflowSlot(), traced[i], rays, predictedRequests_.pixels[i]);
        f.newSamples += static_cast<std::int64_t>(traced.size());
        f.stats.predicted = static_cast<std::int64_t>(traced.size());
    }
    f.stats.traceMs += millisecondsSince(start);
}

}  // namespace raycache
