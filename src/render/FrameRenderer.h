#pragma once
// The ray pipeline's frame: every 16x16 tile goes through the tile kernel
// (render/TileKernel.h) starting from its camera rays, tiles spread over the
// worker threads.
#include "core/Image.h"
#include "core/Parallel.h"
#include "render/FrameStats.h"
#include "render/RenderSettings.h"
#include "render/TileKernel.h"
#include "scene/Camera.h"

namespace raycache {

class FrameRenderer {
public:
    // With `cache` (may be null), caching objects' secondary rays go through
    // it, and its frame hooks run around every frame.
    FrameRenderer(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                  const Parallel& parallel, RayCache* cache = nullptr);

    // Fills `film` (resized to the settings' size) with linear radiance and
    // returns what the frame did. Images and caches do not depend on the
    // thread count.
    FrameStats render(const Camera& camera, Image& film) const;

private:
    RenderSettings settings_;
    const Parallel& parallel_;
    RayCache* cache_;
    TileKernel kernel_;
    // Per-worker buffers kept from frame to frame (render() is not reentrant).
    mutable std::vector<TileScratch> scratch_;
};

// The key that orders a tile's cache stores: its index in row-major tile order.
inline std::uint64_t tileKey(const TileRange& tile, int width, int tileSize) {
    const auto tilesPerRow = static_cast<std::uint64_t>((width + tileSize - 1) / tileSize);
    return static_cast<std::uint64_t>(tile.y0 / tileSize) * tilesPerRow + static_cast<std::uint64_t>(tile.x0 / tileSize);
}

}  // namespace raycache
