#pragma once
// One frame of the caches, owned by one object: the workers' views are made
// and the frame begun on construction; finish() runs improved CDCT's pre-fill
// and merges the queued stores. Caches change only there, never inside the
// kernel's stages.
//
// In a job of several processes (core/ProcessGroup.h) each process renders
// some tiles; finish() first hands every process the stores and counters all
// the others queued (one allGather), so every process merges the same
// batches in the same key order and the caches stay identical everywhere.
#include <optional>
#include <span>

#include "cache/RayCache.h"
#include "core/Parallel.h"
#include "core/ProcessGroup.h"
#include "core/RayCounts.h"

namespace raycache {

class TileKernel;

// What the store exchange of a cluster job fills every frame, kept by the
// renderer from frame to frame so that megabytes of stores do not land in
// freshly allocated pages each frame.
struct StoreExchangeBuffers {
    Bytes packed;            // this process's stores and counters
    GatheredBytes gathered;  // every process's
};

class CacheFrame {
public:
    // `cache` null or empty: an inactive frame, whose workers are null.
    // `group` (may be null: one process) and `buffers` (needed only with a
    // group of several processes) must outlive the frame.
    // `recordsLevels`: the frame records what the cache did per pixel
    // (render/CacheLevelImage.h), which must see the rays leaving caching
    // objects even when every cube stands aside: its workers are kept.
    CacheFrame(RayCache* cache, int workerCount, const ProcessGroup* group = nullptr,
               StoreExchangeBuffers* buffers = nullptr, bool recordsLevels = false);
    // A frame left unfinished (an exception in the middle) is ended without
    // its statistics, so the cache is ready for the next frame.
    ~CacheFrame();
    CacheFrame(const CacheFrame&) = delete;
    CacheFrame& operator=(const CacheFrame&) = delete;

    // Worker `index`'s view of the frame, null when the frame is inactive or
    // when every cube stands aside (RayCache::anyCubeAsks; unless it records
    // levels): the kernel then
    // renders the frame exactly as without a cache. Its other paths (lookups
    // in lanes, dependency tracking in animated scenes, bypass counting) cost
    // a frame a measurable share (docs/log/2026-11-27-policy-that-never-costs.md)
    // for rays no cube would look at.
    CacheWorker* worker(int index) { return asks_ ? &workers_[static_cast<std::size_t>(index)] : nullptr; }

    // Exchanges the queued stores with the other processes (if any),
    // pre-fills the cubes the frame asked for on any process (adding the
    // rays this process traced for them to `rays`: the processes share the
    // pre-fill, render/CachePrefill.h), then applies the queued stores; the
    // frame's cache statistics, summed over the processes, or nothing when
    // inactive.
    std::optional<FrameCacheStats> finish(const TileKernel& kernel, const Parallel& parallel, RayCounts& rays);

    // Bytes the exchange moved: every process's packed stores, summed (what
    // each process receives, its own included). 0 for one process.
    std::size_t exchangedBytes() const { return exchangedBytes_; }
    // Bytes of pre-filled texel rows exchanged (every process's, summed).
    std::size_t prefillBytes() const { return prefillBytes_; }

private:
    RayCache* cache_;
    const ProcessGroup* group_;
    StoreExchangeBuffers* buffers_;
    int localWorkers_ = 0;
    bool asks_ = false;  // some cube looks up this frame
    // The local workers first, then one per other process, filled by the exchange.
    std::span<CacheWorker> workers_;
    std::size_t exchangedBytes_ = 0;
    std::size_t prefillBytes_ = 0;
    bool finished_ = false;
};

}  // namespace raycache
