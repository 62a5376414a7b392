#include "cache/CacheWorker.h"

#include <stdexcept>

namespace raycache {

namespace {

struct PackedBatch {
    std::uint64_t key;
    std::uint64_t stores;
};

// Reads a per-store array pack() wrote (its count, then its values) into
// `out`: none, or one per store.
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

void CacheWorker::pack(std::span<const CacheWorker> workers, Bytes& out) {
    std::vector<PackedBatch> batches;
    std::vector<Counters> counters;
    std::size_t stores = 0, trees = 0, seen = 0;
    // The stores of batch b of worker w are [begin, end) of its pending arrays.
    const auto batchEnd = [](const CacheWorker& w, std::size_t b) {
        // The last batch is still open (closeBatch sets its end at endFrame).
        return b + 1 == w.batches_.size() ? w.pending_.size() : w.batches_[b].end;
    };
    for (const CacheWorker& w : workers) {
        if (counters.size() < w.counters_.size()) counters.resize(w.counters_.size());
        for (std::size_t c = 0; c < w.counters_.size(); ++c) counters[c] += w.counters_[c];
        for (std::size_t b = 0; b < w.batches_.size(); ++b) {
            const std::size_t begin = w.batches_[b].begin, end = batchEnd(w, b);
            if (end <= begin) continue;
            batches.push_back({w.batches_[b].key, end - begin});
            stores += end - begin;
            if (!w.pendingTrees_.empty()) trees += end - begin;
            if (!w.pendingSeen_.empty()) seen += end - begin;
        }
    }
    // One pass per per-store array, straight from the workers into `out`,
    // whose capacity is kept from frame to frame.
    const auto appendRanges = [&](const auto member) {
        for (const CacheWorker& w : workers) {
            const auto& source = w.*member;
            if (source.empty()) continue;  // an array the cache does not keep, e.g. ray trees of a still scene
            for (std::size_t b = 0; b < w.batches_.size(); ++b) {
                const std::size_t begin = w.batches_[b].begin, end = batchEnd(w, b);
                if (end > begin) appendBytes(out, std::span(source).subspan(begin, end - begin));
            }
        }
    };
    out.clear();
    out.reserve(2 * sizeof(std::uint64_t) + counters.size() * sizeof(Counters) + batches.size() * sizeof(PackedBatch) +
                stores * sizeof(PendingStore) + sizeof(std::uint64_t) + trees * sizeof(RayTreeRecord) +
                sizeof(std::uint64_t) + seen * sizeof(SeenPoint));
    appendBytes(out, static_cast<std::uint64_t>(counters.size()));
    appendBytes(out, static_cast<std::uint64_t>(batches.size()));
    appendBytes(out, std::span<const Counters>(counters));
    appendBytes(out, std::span<const PackedBatch>(batches));
    appendRanges(&CacheWorker::pending_);
    appendBytes(out, static_cast<std::uint64_t>(trees));
    appendRanges(&CacheWorker::pendingTrees_);
    appendBytes(out, static_cast<std::uint64_t>(seen));
    appendRanges(&CacheWorker::pendingSeen_);
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
