#include "render/CacheFrame.h"

#include "render/CachePrefill.h"

namespace raycache {

CacheFrame::CacheFrame(RayCache* cache, int workerCount) : cache_(cache && !cache->empty() ? cache : nullptr) {
    if (!cache_) return;
    workers_ = cache_->reusableWorkers(workerCount);
    cache_->beginFrame(workers_);
}

CacheFrame::~CacheFrame() {
    if (cache_ && !finished_) cache_->endFrame(workers_);
}

std::optional<FrameCacheStats> CacheFrame::finish(const TileKernel& kernel, const Parallel& parallel,
                                                  RayCounts& rays) {
    if (!cache_ || finished_) return std::nullopt;
    finished_ = true;
    rays += prefillCaches(*cache_, workers_, kernel, parallel);
    return cache_->endFrame(workers_, [&](int count, const std::function<void(int)>& body) {
        parallel.forEachIndex(count, [&](int part, int) { body(part); });
    });
}

}  // namespace raycache
