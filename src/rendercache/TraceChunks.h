#pragma once
// How the Render Cache pipeline hands pixels and surfaces to the tile
// kernel: in fixed chunks, whose index orders the caches' stores (so images
// and caches do not depend on the thread count).
#include <algorithm>
#include <cstddef>

#include "core/Parallel.h"

namespace raycache {

// Pixels handed to the tile kernel at once: enough for full packets and
// waves, few enough to spread over the workers.
inline constexpr std::size_t kTraceChunk = 256;

// How many chunks of kTraceChunk make `count`.
inline std::size_t traceChunkCount(std::size_t count) { return (count + kTraceChunk - 1) / kTraceChunk; }

// Runs body(begin, end, chunk, worker) over [0, count) in chunks of
// kTraceChunk on all threads; the chunk index orders the cache's stores
// where the body traces.
template <typename Body>
void forEachTraceChunk(const Parallel& parallel, std::size_t count, const Body& body) {
    parallel.forEachIndex(static_cast<int>(traceChunkCount(count)), [&](int chunk, int worker) {
        const std::size_t begin = static_cast<std::size_t>(chunk) * kTraceChunk;
        body(begin, std::min(count, begin + kTraceChunk), chunk, worker);
    });
}

}  // namespace raycache
