#pragma once
// One worker thread's view of the caches during a frame: the stores it wants
// to make (merged by RayCache::endFrame) and its counters. Owned by the frame
// (render/CacheFrame.h), one per worker, so nothing here is shared between threads.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "cache/CacheStats.h"
#include "cache/CoarseLevels.h"
#include "cache/RayTreeRecord.h"
#include "cache/ViewSizedResolution.h"
#include "core/ProcessGroup.h"

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

    // What `workers` queued this frame (their non-empty batches with their
    // stores, in worker then queue order, and their lookup counters summed
    // per cube) as bytes for the other processes of a cluster job
    // (src/cluster/): 20 bytes per store, 16 per batch, sizeof(Counters) per cube; in an
    // animated scene also each store's RayTreeRecord (156 bytes); with
    // multi-resolution cubes each store's SeenPoint (16 bytes). Written into
    // `out` (replacing what it held; its capacity is reused).
    static void pack(std::span<const CacheWorker> workers, Bytes& out);
    // Makes this worker hold what pack() packed in another process, so that
    // its batches join RayCache::endFrame's merge (in key order, like any
    // worker's) and its counters the frame's statistics. Throws
    // std::runtime_error for a message that does not match `cubeCount`.
    void unpack(std::span<const std::byte> bytes, std::size_t cubeCount);

private:
    friend class RayCache;

    struct PendingStore {
        std::uint32_t cube;    // index into RayCache's cubes
        std::int32_t texel;
        std::uint32_t packed;  // encoded color
        float depth;           // CDCT: distance from the cube's centre; unused by CCT
        // Rays the stored ray's tree traced (for the cache policy's record of
        // what a hit on this texel spares); 0 when not counted.
        std::uint32_t treeRays;
    };
    struct Batch {
        std::uint64_t key;
        std::size_t begin, end;  // [begin, end) of pending_
    };
    struct Counters {
        std::uint64_t lookups = 0, hits = 0, misses = 0, rejected = 0;
        std::uint64_t ownSurface = 0;  // of the misses: rays meeting their own object (Query::meetsOwnSurface)
        std::uint64_t viewDependent = 0;  // of the misses: CDCT rays meeting a texel that saw a mirror or glass
        std::array<std::uint64_t, kMaxCubeLevels> levelHits{};  // of the hits, per level (0: the finest)
        std::uint64_t cdctSearches = 0, cdctSteps = 0;
        // The cache policy's counts (cache/CachePolicy.h): rays that passed a
        // cube standing aside, stores asked for, and the traced trees handed
        // to store() with the rays each traced.
        std::uint64_t bypassed = 0, queuedStores = 0, tracedTrees = 0, treeRays = 0;
        // Hits on sampled texels that recorded the tree they hold, and those
        // trees' rays in all (RayCache's per-texel record, `auto` CCT cubes).
        std::uint64_t recordedHits = 0, recordedHitRays = 0;
        std::array<std::uint64_t, kCdctStepBuckets> cdctStepsHistogram{};
        // View-sized cubes: lookups by the coarsest level their footprint
        // allows (ViewSizedResolution::levelAllowed).
        ViewSizedResolution::LookupsByLevel lookupsByAllowedLevel{};

        void countCdctSearch(int steps) {
            const auto n = static_cast<std::uint64_t>(steps);
            ++cdctSearches;
            cdctSteps += n;
            ++cdctStepsHistogram[static_cast<std::size_t>(cdctStepBucket(n))];
        }
        Counters& operator+=(const Counters& o) {
            lookups += o.lookups;
            hits += o.hits;
            misses += o.misses;
            rejected += o.rejected;
            ownSurface += o.ownSurface;
            viewDependent += o.viewDependent;
            for (std::size_t k = 0; k < levelHits.size(); ++k) levelHits[k] += o.levelHits[k];
            cdctSearches += o.cdctSearches;
            cdctSteps += o.cdctSteps;
            bypassed += o.bypassed;
            queuedStores += o.queuedStores;
            tracedTrees += o.tracedTrees;
            treeRays += o.treeRays;
            recordedHits += o.recordedHits;
            recordedHitRays += o.recordedHitRays;
            for (std::size_t k = 0; k < cdctStepsHistogram.size(); ++k) cdctStepsHistogram[k] += o.cdctStepsHistogram[k];
            for (std::size_t k = 0; k < lookupsByAllowedLevel.size(); ++k)
                lookupsByAllowedLevel[k] += o.lookupsByAllowedLevel[k];
            return *this;
        }
    };

    void closeBatch() {
        if (!batches_.empty()) batches_.back().end = pending_.size();
    }
    void queue(const PendingStore& store) {
        if (batches_.empty()) batches_.push_back({0, 0, 0});
        pending_.push_back(store);
    }

    std::vector<PendingStore> pending_;
    // When the cache tracks what its texels depend on (animated scenes): the
    // tree of each pending store, same index.
    std::vector<RayTreeRecord> pendingTrees_;
    // When the cache has multi-resolution cubes: what each pending store's
    // ray saw (cache/CoarseLevels.h), same index.
    std::vector<SeenPoint> pendingSeen_;
    std::vector<Batch> batches_;
    std::vector<Counters> counters_;  // per cube
};

}  // namespace raycache
