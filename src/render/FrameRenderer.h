#pragma once
// The ray pipeline's frame: every 16x16 tile goes through the tile kernel
// (render/TileKernel.h) starting from its camera rays, tiles spread over the
// worker threads, and in a job of several processes (core/ProcessGroup.h)
// over the processes: each renders its share of the tiles, the cache stores
// are exchanged (render/CacheFrame.h) and process 0 gathers the image.
#include <algorithm>

#include "core/Image.h"
#include "core/Parallel.h"
#include "core/ProcessGroup.h"
#include "render/CacheFrame.h"
#include "render/CacheLevelImage.h"
#include "render/FrameStats.h"
#include "render/RenderSettings.h"
#include "render/TileKernel.h"
#include "scene/Camera.h"

namespace raycache {

class FrameRenderer {
public:
    // With `cache` (may be null), caching objects' secondary rays go through
    // it, and its frame hooks run around every frame.
    // `group` (may be null: one process) must outlive the renderer. Throws
    // InputError for settings.recordCacheLevels with several processes.
    FrameRenderer(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                  const Parallel& parallel, RayCache* cache = nullptr, const ProcessGroup* group = nullptr);

    // Fills `film` (resized to the settings' size) with linear radiance and
    // returns what the frame did. Images and caches do not depend on the
    // thread count, nor on the process count. With several processes, only
    // process 0's film is whole and only its statistics are the job's (the
    // cache statistics are the job's on every process); every process must
    // call render() for every frame.
    // With settings.recordCacheLevels and `levels`, `levels` (resized to the
    // film's size) gets the frame's cache-level record; otherwise it is not
    // touched. The film is the same either way.
    // With `samples`, every pixel's ray passes through its sample `sample`
    // (render/PixelSamples.h) instead of its centre.
    FrameStats render(const Camera& camera, Image& film, CacheLevelImage* levels = nullptr,
                      const PixelSamples* samples = nullptr, int sample = 0) const;

private:
    FrameStats renderDistributed(const CameraRays& cameraRays, Image& film) const;

    RenderSettings settings_;
    const Parallel& parallel_;
    RayCache* cache_;
    const ProcessGroup* group_;
    TileKernel kernel_;
    // Process 0: each tile's kernel time in the last distributed frame, for
    // TileBalance::Dynamic (empty before the first).
    mutable std::vector<double> lastTileCosts_;
    // Per-worker buffers kept from frame to frame (render() is not reentrant).
    mutable std::vector<TileScratch> scratch_;
    // A cluster job's exchanges, kept from frame to frame: the cache stores,
    // this process's tiles for process 0, and on process 0 every process's.
    mutable StoreExchangeBuffers storeExchange_;
    mutable Bytes imagePart_;
    mutable std::vector<Bytes> workerPixels_;  // workers 1, 2, ...: their tiles' pixels (worker 0's go into imagePart_)
    mutable GatheredBytes imageParts_;
};

// Tile `index` of a frame (row-major, as tileKey counts) clipped to the image.
inline TileRange tileAt(int index, int width, int height, int tileSize) {
    const int tilesPerRow = (width + tileSize - 1) / tileSize;
    const int x0 = (index % tilesPerRow) * tileSize, y0 = (index / tilesPerRow) * tileSize;
    return {x0, y0, std::min(x0 + tileSize, width), std::min(y0 + tileSize, height)};
}

inline int tileCount(int width, int height, int tileSize) {
    return ((width + tileSize - 1) / tileSize) * ((height + tileSize - 1) / tileSize);
}

// The key that orders a tile's cache stores: its index in row-major tile order.
inline std::uint64_t tileKey(const TileRange& tile, int width, int tileSize) {
    const auto tilesPerRow = static_cast<std::uint64_t>((width + tileSize - 1) / tileSize);
    return static_cast<std::uint64_t>(tile.y0 / tileSize) * tilesPerRow + static_cast<std::uint64_t>(tile.x0 / tileSize);
}

}  // namespace raycache
