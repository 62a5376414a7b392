#pragma once
// Improved CDCT's pre-fill: a cube the frame asked
// for is filled whole from its centre, so the search never meets an invalid
// texel (the thesis's main cause of failed lookups). By default before the
// next frame; with RayCacheSettings::prefillTexelsPerFrame, a budget of face
// rows per frame, so no frame stalls on it (RayCache::planPrefill).
#include <span>

#include "cache/RayCache.h"
#include "core/Parallel.h"
#include "core/ProcessGroup.h"
#include "core/RayCounts.h"

namespace raycache {

class TileKernel;

// Traces one ray per texel of this frame's pre-fill pieces (RayCache::
// planPrefill after the frame `workers` rendered), through the tile
// kernel's pre-fill stage (uncached, so the result depends only on the
// scene), and hands the cubes their contents. Call after the frame's pixels
// and before RayCache::endFrame. Deterministic: each texel is computed on
// its own, whatever the thread count.
//
// With `group` of several processes (collective: every process must call
// it, with workers that saw every process's lookup counters), face row i of
// each piece is traced by process i mod N and the rows are allgathered (16
// bytes per texel), so every process gets the same cubes for 1/N of the rays.
struct PrefillResult {
    RayCounts rays;                   // traced by this process
    std::uint64_t exchangedBytes = 0;  // every process's rows, summed (0 for one process)
};
PrefillResult prefillCaches(RayCache& cache, std::span<const CacheWorker> workers, const TileKernel& kernel,
                            const Parallel& parallel, const ProcessGroup* group = nullptr);

}  // namespace raycache
