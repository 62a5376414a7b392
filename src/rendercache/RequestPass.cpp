// RenderCachePipeline's request map: how many rays this frame traces, and
// where (rendercache/RequestMap.h); every pixel on the first frame and
// after a cut.
#include <cmath>

#include "core/Elapsed.h"
#include "rendercache/RenderCacheFrameContext.h"
#include "rendercache/RequestMap.h"

namespace raycache {

namespace {

// Every pixel of the image, 16x16 tile by tile (coherent packets).
void everyPixelByTiles(int width, int height, std::vector<PixelCoord>& out) {
    constexpr int kTile = 16;
    out.clear();
    out.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int ty = 0; ty < height; ty += kTile)
        for (int tx = 0; tx < width; tx += kTile)
            for (int y = ty; y < std::min(height, ty + kTile); ++y)
                for (int x = tx; x < std::min(width, tx + kTile); ++x) out.push_back({x, y});
}

}  // namespace

void RenderCachePipeline::requestSamples(FrameContext& f) {
    const auto start = std::chrono::steady_clock::now();
    const RenderCacheSettings& rc = f.rc;
    RenderCacheStats& stats = f.stats;
    const int width = f.width, height = f.height, pixels = f.pixels;
    stats.refreshedAll =
        !previousCamera_ || static_cast<double>(f.holes) > static_cast<double>(rc.refreshAllHoleShare) * pixels;
    f.budget = stats.refreshedAll                      ? pixels
               : f.async && f.async->budget > 0 ? std::min(f.async->budget, pixels)
                                                : chooseBudget(pixels);
    stats.budget = f.wantsRequests ? f.budget : 0;
    f.predictedBudget = (f.moved && !stats.refreshedAll && f.wantsRequests)
                            ? static_cast<int>(std::lround(static_cast<double>(f.budget) * rc.predictShare))
                            : 0;
    RequestMap& requests = overlays_.requests;
    overlays_.width = width;
    overlays_.height = height;
    if (!f.wantsRequests) {
        requests.pixels.clear();
        requests.tileRequests.clear();
        requests.tilePriority.clear();
    } else if (stats.refreshedAll) {
        everyPixelByTiles(width, height, requests.pixels);
        requests.tileRequests.clear();
        requests.tilePriority.clear();
    } else {
        buildRequestMap(priority_, width, height, rc.requestTileSize, rc.alpha, f.budget - f.predictedBudget, rc.seed,
                        frame_, requests, parallel_);
    }
    stats.mapsMs += millisecondsSince(start);
    ReconstructionCounts& touched = f.touched;
    touched.everyPixelRequested = f.wantsRequests && stats.refreshedAll;
    touched.requestMap = f.wantsRequests && !stats.refreshedAll;
    if (touched.requestMap) {
        touched.tiles = static_cast<std::int64_t>(requests.tileRequests.size());
        touched.requested = static_cast<std::int64_t>(requests.pixels.size());
        touched.pixelsInRequestedTiles = pixelsInTilesWithRequests(requests, width, height);
    }
}

}  // namespace raycache
