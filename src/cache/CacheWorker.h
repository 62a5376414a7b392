#pragma once
// One worker thread's view of the caches during a frame: the stores it wants
// to make (merged by RayCache::endFrame) and its counters. Owned by the frame
// (render/CacheFrame.h), one per worker, so nothing here is shared between threads.
#include <cstdint>
#include <vector>

namespace raycache {

class CacheWorker {
public:
    // Stores queued after this call belong to batch `key` (the tile kernel
    // uses the tile's index). At the end of the frame the batches of all
    // workers are applied in increasing key order, each batch's stores in the
    // order they were queued, and the first store to an invalid texel wins:
    // the order does not depend on which thread ran a batch. Keys must be
    // unique within a frame.
    void beginBatch(std::uint64_t key) {
        closeBatch();
        batches_.push_back({key, pending_.size(), pending_.size()});
    }

private:
    friend class RayCache;

    struct PendingStore {
        std::uint32_t cube;    // index into RayCache's cubes
        std::int32_t texel;
        std::uint32_t packed;  // encoded color
        float depth;           // CDCT: distance from the cube's centre; unused by CCT
    };
    struct Batch {
        std::uint64_t key;
        std::size_t begin, end;  // [begin, end) of pending_
    };
    struct Counters {
        std::uint64_t lookups = 0, hits = 0, misses = 0, rejected = 0;
    };

    void closeBatch() {
        if (!batches_.empty()) batches_.back().end = pending_.size();
    }
    void queue(const PendingStore& store) {
        if (batches_.empty()) batches_.push_back({0, 0, 0});
        pending_.push_back(store);
    }

    std::vector<PendingStore> pending_;
    std::vector<Batch> batches_;
    std::vector<Counters> counters_;  // per cube
};

}  // namespace raycache
