// RenderCachePipeline's new samples: the requested pixels traced through the
// frame's camera by the tile kernel, each replacing what its pixel held;
// the asynchronous mode hands the request to its tracer instead.
#include <atomic>
#include <limits>

#include "core/Elapsed.h"
#include "render/CameraRays.h"
#include "rendercache/RenderCacheFrameContext.h"
#include "rendercache/TraceChunks.h"

namespace raycache {

void RenderCachePipeline::traceNewSamples(FrameContext& f) {
    const auto start = std::chrono::steady_clock::now();
    const RequestMap& requests = overlays_.requests;
    std::vector<PrimarySample>& traced = traced_;
    if (f.async) {
        traced.clear();
        if (f.async->request) {
            f.async->request->camera = f.camera;
            f.async->request->pixels = requests.pixels;
            f.async->request->predicted.clear();
            f.async->request->refreshesAll = f.stats.refreshedAll;
        }
        f.stats.fresh = 0;
        f.stats.traceMs = millisecondsSince(start);
        return;
    }
    f.cacheFrame.emplace(cache_, parallel_.threadCount());
    f.key = trace(f.camera, requests.pixels, 0, *f.cacheFrame, traced);
    // On all threads: the requested pixels are distinct, and each one's
    // writes touch only its own slot, key and state, and on one thread this
    // loop waits on its cache misses.
    const int width = f.width;
    std::vector<PixelState>& state = overlays_.state;
    const CameraRays rays(f.camera, width, f.height);
    std::vector<std::int64_t> newPerChunk(traceChunkCount(traced.size()), 0);
    std::vector<std::int64_t> replacedPerChunk(traceChunkCount(traced.size()), 0);
    forEachTraceChunk(parallel_, traced.size(), [&](std::size_t begin, std::size_t end, int chunk, int) {
        std::int64_t fresh = 0, replaced = 0;
        for (std::size_t i = begin; i < end; ++i) {
            const PixelCoord p = requests.pixels[i];
            const std::size_t slot = image_.pixelIndex(p.x, p.y);
            fresh += image_.hasSample(p.x, p.y) ? 0 : 1;
            PixelState& s = state[static_cast<std::size_t>(p.y * width + p.x)];
            // A reprojected sample replaced is not reshaded: out of its row's count.
            if (s == PixelState::Reprojected && f.reshading.chooses(pool_.look[slot], p.x, p.y))
                std::atomic_ref<std::size_t>(reshadeRowStart_[static_cast<std::size_t>(p.y) + 1])
                    .fetch_sub(1, std::memory_order_relaxed);
            keep(slot, traced[i], rays, p);
            int px, py;
            float depth = std::numeric_limits<float>::infinity();  // a camera ray's hit is never behind the eye
            projectSample(pool_, slot, f.origins, f.projection, px, py, depth);
            // Placed where it was traced, whatever rounding says about the reprojection.
            image_.place(p.x, p.y, depth);
            replaced += s == PixelState::Reprojected ? 1 : 0;
            s = PixelState::Fresh;
            if (f.predictedBudget > 0)
                nextPixel_[slot] = imagePixelThrough(pool_, slot, f.origins, f.nextProjection, width, f.height);
        }
        newPerChunk[static_cast<std::size_t>(chunk)] = fresh;
        replacedPerChunk[static_cast<std::size_t>(chunk)] = replaced;
    });
    for (std::int64_t n : newPerChunk) f.newSamples += n;
    for (std::int64_t n : replacedPerChunk) f.stats.reprojected -= n;
    f.stats.fresh = static_cast<std::int64_t>(traced.size());
    f.stats.traceMs = millisecondsSince(start);
}

}  // namespace raycache
