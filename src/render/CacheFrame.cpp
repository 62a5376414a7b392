#include "render/CacheFrame.h"

#include "render/CachePrefill.h"

#include <stdexcept>

namespace raycache {

namespace {

bool distributed(const ProcessGroup* group) { return group && group->size() > 1; }

}  // namespace

CacheFrame::CacheFrame(RayCache* cache, int workerCount, const ProcessGroup* group, StoreExchangeBuffers* buffers,
                       bool recordsLevels)
    : cache_(cache && !cache->empty() ? cache : nullptr), group_(group), buffers_(buffers), localWorkers_(workerCount) {
    if (!cache_) return;
    if (distributed(group_) && !buffers_) throw std::logic_error("CacheFrame: a cluster frame needs exchange buffers");
    const int remote = distributed(group_) ? group_->size() - 1 : 0;
    workers_ = cache_->reusableWorkers(workerCount + remote);
    cache_->beginFrame(workers_);
    // Every process holds the same policy states, so all decide alike.
    asks_ = recordsLevels || cache_->anyCubeAsks();
}

CacheFrame::~CacheFrame() {
    if (cache_ && !finished_) cache_->endFrame(workers_);
}

std::optional<FrameCacheStats> CacheFrame::finish(const TileKernel& kernel, const Parallel& parallel,
                                                  RayCounts& rays) {
    if (!cache_ || finished_) return std::nullopt;
    finished_ = true;
    if (distributed(group_)) {
        CacheWorker::pack(workers_.first(static_cast<std::size_t>(localWorkers_)), buffers_->packed);
        GatheredBytes& all = buffers_->gathered;
        group_->allGather(buffers_->packed, all);
        std::size_t slot = static_cast<std::size_t>(localWorkers_);
        for (std::size_t r = 0; r < all.count(); ++r) {
            exchangedBytes_ += all.of(r).size();
            if (static_cast<int>(r) != group_->rank()) workers_[slot++].unpack(all.of(r), cache_->cubeCount());
        }
    }
    // With the other processes' counters in workers_, every process sees the
    // same cubes asked for and pre-fills the same ones, sharing their rows.
    const PrefillResult prefill =
        prefillCaches(*cache_, workers_, kernel, parallel, distributed(group_) ? group_ : nullptr);
    rays += prefill.rays;
    prefillBytes_ = prefill.exchangedBytes;
    FrameCacheStats stats = cache_->endFrame(
        workers_,
        [&](int count, const std::function<void(int)>& body) {
            parallel.forEachIndex(count, [&](int part, int) { body(part); });
        },
        parallel.threadCount());
    stats.tracedAsUncached = !asks_;  // (a frame recording levels counts its bypassed rays)
    return stats;
}

}  // namespace raycache
