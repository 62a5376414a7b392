#include "cache/CacheWorker.h"

#include <stdexcept>

namespace raycache {

namespace {

struct PackedBatch {
    std::uint64_t key;
    std::uint64_t stores;
};

}  // namespace

Bytes CacheWorker::pack(std::span<const CacheWorker> workers) {
    std::vector<PackedBatch> batches;
    std::vector<PendingStore> stores;
    std::vector<RayTreeRecord> trees;  // animated scenes: one per store
    std::vector<SeenPoint> seen;       // multi-resolution cubes: one per store
    std::vector<Counters> counters;
    for (const CacheWorker& w : workers) {
        if (counters.size() < w.counters_.size()) counters.resize(w.counters_.size());
        for (std::size_t c = 0; c < w.counters_.size(); ++c) {
            counters[c].lookups += w.counters_[c].lookups;
            counters[c].hits += w.counters_[c].hits;
            counters[c].misses += w.counters_[c].misses;
            counters[c].rejected += w.counters_[c].rejected;
            for (std::size_t k = 0; k < counters[c].levelHits.size(); ++k)
                counters[c].levelHits[k] += w.counters_[c].levelHits[k];
        }
        for (std::size_t b = 0; b < w.batches_.size(); ++b) {
            // The last batch is still open (closeBatch sets its end at endFrame).
            const std::size_t end = b + 1 == w.batches_.size() ? w.pending_.size() : w.batches_[b].end;
            const std::size_t begin = w.batches_[b].begin;
            if (end <= begin) continue;
            batches.push_back({w.batches_[b].key, end - begin});
            stores.insert(stores.end(), w.pending_.begin() + static_cast<std::ptrdiff_t>(begin),
                          w.pending_.begin() + static_cast<std::ptrdiff_t>(end));
            if (!w.pendingTrees_.empty())
                trees.insert(trees.end(), w.pendingTrees_.begin() + static_cast<std::ptrdiff_t>(begin),
                             w.pendingTrees_.begin() + static_cast<std::ptrdiff_t>(end));
            if (!w.pendingSeen_.empty())
                seen.insert(seen.end(), w.pendingSeen_.begin() + static_cast<std::ptrdiff_t>(begin),
                            w.pendingSeen_.begin() + static_cast<std::ptrdiff_t>(end));
        }
    }
    Bytes bytes;
    appendBytes(bytes, static_cast<std::uint64_t>(counters.size()));
    appendBytes(bytes, static_cast<std::uint64_t>(batches.size()));
    appendBytes(bytes, std::span<const Counters>(counters));
    appendBytes(bytes, std::span<const PackedBatch>(batches));
    appendBytes(bytes, std::span<const PendingStore>(stores));
    appendBytes(bytes, static_cast<std::uint64_t>(trees.size()));
    appendBytes(bytes, std::span<const RayTreeRecord>(trees));
    appendBytes(bytes, static_cast<std::uint64_t>(seen.size()));
    appendBytes(bytes, std::span<const SeenPoint>(seen));
    return bytes;
}

void CacheWorker::unpack(std::span<const std::byte> bytes, std::size_t cubeCount) {
    ByteReader reader(bytes);
    const auto cubes = reader.read<std::uint64_t>();
    const auto batchCount = reader.read<std::uint64_t>();
    if (cubes != cubeCount && cubes != 0)
        throw std::runtime_error("cache stores from another process name " + std::to_string(cubes) +
                                 " cubes, this process has " + std::to_string(cubeCount));
    counters_.assign(cubeCount, Counters{});
    reader.readInto(std::span<Counters>(counters_.data(), cubes));
    std::vector<PackedBatch> packed(batchCount);
    reader.readInto(std::span<PackedBatch>(packed));
    batches_.clear();
    pending_.clear();
    std::size_t total = 0;
    for (const PackedBatch& b : packed) {
        batches_.push_back({b.key, total, total + b.stores});
        total += b.stores;
    }
    pending_.resize(total);
    reader.readInto(std::span<PendingStore>(pending_));
    const auto treeCount = reader.read<std::uint64_t>();
    if (treeCount != 0 && treeCount != total)
        throw std::runtime_error("cache stores from another process: " + std::to_string(treeCount) +
                                 " ray-tree records for " + std::to_string(total) + " stores");
    pendingTrees_.resize(treeCount);
    reader.readInto(std::span<RayTreeRecord>(pendingTrees_));
    const auto seenCount = reader.read<std::uint64_t>();
    if (seenCount != 0 && seenCount != total)
        throw std::runtime_error("cache stores from another process: " + std::to_string(seenCount) +
                                 " seen points for " + std::to_string(total) + " stores");
    pendingSeen_.resize(seenCount);
    reader.readInto(std::span<SeenPoint>(pendingSeen_));
    if (!reader.atEnd()) throw std::runtime_error("cache stores from another process: trailing bytes");
    for (const PendingStore& s : pending_)
        if (s.cube >= cubeCount) throw std::runtime_error("cache stores from another process name a cube out of range");
}

}  // namespace raycache
