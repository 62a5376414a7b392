#include "render/FrameRenderer.h"

#include <chrono>
#include <vector>

#include "render/CacheFrame.h"
#include "render/CameraRays.h"

namespace raycache {

FrameRenderer::FrameRenderer(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                             const Parallel& parallel, RayCache* cache)
    : settings_(settings), parallel_(parallel), cache_(cache && !cache->empty() ? cache : nullptr),
      kernel_(scene, tracer, settings, cache_) {}

FrameStats FrameRenderer::render(const Camera& camera, Image& film) const {
    if (film.width() != settings_.width || film.height() != settings_.height)
        film = Image(settings_.width, settings_.height);
    const CameraRays cameraRays(camera, settings_.width, settings_.height);
    std::vector<TileScratch>& scratch = scratch_;
    scratch.resize(static_cast<std::size_t>(parallel_.threadCount()));
    for (TileScratch& s : scratch) s.beginFrame();
    CacheFrame cacheFrame(cache_, parallel_.threadCount());
    parallel_.forEachTile(settings_.width, settings_.height, settings_.tileSize, [&](const TileRange& tile, int worker) {
        kernel_.renderCameraTile(cameraRays, tile, tileKey(tile, settings_.width, settings_.tileSize),
                                 scratch[static_cast<std::size_t>(worker)], cacheFrame.worker(worker), film);
    });

    FrameStats stats;
    StageTimes stages;
    for (const TileScratch& s : scratch) {
        stats.rays += s.counts;
        stages += s.stages;
    }
    const auto start = std::chrono::steady_clock::now();
    stats.cache = cacheFrame.finish(kernel_, parallel_, stats.rays);
    if (settings_.stageTimes) {
        stages.cacheFrameEnd =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        stats.stages = stages;
    }
    return stats;
}

}  // namespace raycache
