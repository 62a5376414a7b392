#include "render/DeferredShading.h"

#include <chrono>
#include <vector>

#include "core/Elapsed.h"
#include "render/CacheFrame.h"
#include "render/CameraRays.h"
#include "render/FrameRenderer.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

DeferredShading::DeferredShading(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                                 const Parallel& parallel, RayCache* cache)
    : settings_(settings), parallel_(parallel), cache_(cache && !cache->empty() ? cache : nullptr),
      kernel_(scene, tracer, settings, cache_) {}

void DeferredShading::shade(const Camera& camera, const GBufferView& gbuffer, Image& film, FrameStats& stats,
                            CacheLevelImage* levels) {
    const int width = settings_.width, height = settings_.height;
    if (film.width() != width || film.height() != height) film = Image(width, height);
    if (!settings_.recordCacheLevels) levels = nullptr;
    kernel_.prepareFrame();  // meshes that moved since the last frame
    if (levels && (levels->width() != width || levels->height() != height)) *levels = CacheLevelImage(width, height);
    const CameraRays cameraRays(camera, width, height);
    PhaseTimes& phases = stats.phases.emplace(stats.phases.value_or(PhaseTimes{}));

    const auto frameStart = Clock::now();
    std::vector<TileScratch>& scratch = scratch_;
    scratch.resize(static_cast<std::size_t>(parallel_.threadCount()));
    for (TileScratch& s : scratch) s.beginFrame();
    CacheFrame cacheFrame(cache_, parallel_.threadCount(), nullptr, nullptr, levels != nullptr);
    parallel_.forEachTile(width, height, settings_.tileSize, [&](const TileRange& tile, int worker) {
        kernel_.renderGBufferTile(cameraRays, gbuffer, tile, tileKey(tile, width, settings_.tileSize),
                                  scratch[static_cast<std::size_t>(worker)], cacheFrame.worker(worker), film, levels);
    });
    Clock::duration firstBounce{}, laterBounces{}, compose{};
    StageTimes stages;
    for (const TileScratch& s : scratch) {
        stats.rays += s.counts;
        stages += s.stages;
        firstBounce += s.firstBounce;
        laterBounces += s.laterBounces;
        compose += s.compose;
    }
    const double passMs = millisecondsSince(frameStart);
    const auto mergeStart = Clock::now();
    stats.cache = cacheFrame.finish(kernel_, parallel_, stats.rays);
    const double mergeMs = millisecondsSince(mergeStart);
    const double busy = std::chrono::duration<double>(firstBounce + laterBounces + compose).count();
    const auto share = [&](Clock::duration d) {
        return busy > 0.0 ? passMs * std::chrono::duration<double>(d).count() / busy : 0.0;
    };
    phases.shadows += share(firstBounce);
    phases.secondary += share(laterBounces) + mergeMs;  // the cache merge (and pre-fill) belongs to the secondary rays
    phases.compose += share(compose);
    if (settings_.stageTimes) {
        stages.cacheFrameEnd = mergeMs;
        stats.stages = stages;
    }
}

}  // namespace raycache
