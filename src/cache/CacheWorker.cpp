#include "cache/CacheWorker.h"

#include <stdexcept>

namespace raycache {

namespace {

struct PackedBatch {
    std::uint64_t key;
    std::uint64_t stores;
};

// Appends source[begin, end) to `out`, unless `source` is empty (a per-store
// array the cache does not keep, e.g. ray-tree records of a still scene).
template <typename T>
void appendStoreRange(std::vector<T>& out, const std::vector<T>& source, std::size_t begin, std::size_t end) {
    if (source.empty()) return;
    out.insert(out.end(), source.begin() + static_cast<std::ptrdiff_t>(begin),
               source.begin() + static_cast<std::ptrdiff_t>(end));
}

// Appends the count and the values of a per-store array.
template <typename T>
void appendCounted(Bytes& bytes, const std::vector<T>& values) {
    appendBytes(bytes, static_cast<std::uint64_t>(values.size()));
    appendBytes(bytes, std::span<const T>(values));
}

// Reads what appendCounted wrote into `out`: none, or one per store.
template <typename T>
void readCounted(ByteReader& reader, std::size_t stores, const char* what, std::vector<T>& out) {
    const auto count = reader.read<std::uint64_t>();
    if (count != 0 && count != stores)
        throw std::runtime_error("cache stores from another process: " + std::to_string(count) + " " + what + " for " +
                                 std::to_string(stores) + " stores");
    out.resize(count);
    reader.readInto(std::span<T>(out));
}

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
            appendStoreRange(stores, w.pending_, begin, end);
            appendStoreRange(trees, w.pendingTrees_, begin, end);
            appendStoreRange(seen, w.pendingSeen_, begin, end);
        }
    }
    Bytes bytes;
    appendBytes(bytes, static_cast<std::uint64_t>(counters.size()));
    appendBytes(bytes, static_cast<std::uint64_t>(batches.size()));
    appendBytes(bytes, std::span<const Counters>(counters));
    appendBytes(bytes, std::span<const PackedBatch>(batches));
    appendBytes(bytes, std::span<const PendingStore>(stores));
    appendCounted(bytes, trees);
    appendCounted(bytes, seen);
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
    readCounted(reader, total, "ray-tree records", pendingTrees_);
    readCounted(reader, total, "seen points", pendingSeen_);
    if (!reader.atEnd()) throw std::runtime_error("cache stores from another process: trailing bytes");
    for (const PendingStore& s : pending_)
        if (s.cube >= cubeCount) throw std::runtime_error("cache stores from another process name a cube out of range");
}

}  // namespace raycache
