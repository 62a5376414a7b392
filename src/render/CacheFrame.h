#pragma once
// One frame of the caches, owned by one object: the workers' views are made
// and the frame begun on construction; finish() runs improved CDCT's pre-fill
// and merges the queued stores. Caches change only there, never inside the
// kernel's stages.
#include <optional>
#include <span>

#include "cache/RayCache.h"
#include "core/Parallel.h"
#include "core/RayCounts.h"

namespace raycache {

class TileKernel;

class CacheFrame {
public:
    // `cache` null or empty: an inactive frame, whose workers are null.
    CacheFrame(RayCache* cache, int workerCount);
    // A frame left unfinished (an exception in the middle) is ended without
    // its statistics, so the cache is ready for the next frame.
    ~CacheFrame();
    CacheFrame(const CacheFrame&) = delete;
    CacheFrame& operator=(const CacheFrame&) = delete;

    // Worker `index`'s view of the frame, null when the frame is inactive.
    CacheWorker* worker(int index) { return cache_ ? &workers_[static_cast<std::size_t>(index)] : nullptr; }

    // Pre-fills the cubes the frame asked for (adding their rays to `rays`),
    // then applies the queued stores; the frame's statistics, or nothing when
    // inactive.
    std::optional<FrameCacheStats> finish(const TileKernel& kernel, const Parallel& parallel, RayCounts& rays);

private:
    RayCache* cache_;
    std::span<CacheWorker> workers_;
    bool finished_ = false;
};

}  // namespace raycache
