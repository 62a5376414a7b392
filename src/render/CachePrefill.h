#pragma once
// Improved CDCT's pre-fill (SPEC §3 "what to beat"): a cube the frame asked
// for is filled whole from its centre before the next frame, so the search
// never meets an invalid texel (the thesis's main cause of failed lookups).
#include <span>

#include "cache/RayCache.h"
#include "core/Parallel.h"
#include "core/RayCounts.h"

namespace raycache {

class TileKernel;

// Traces one ray per texel from the centre of every cube `cache` reports as
// awaiting its pre-fill after the frame `workers` rendered, through the tile
// kernel's pre-fill stage (uncached, so the result depends only on the
// scene), and hands the cubes their contents. Call after the frame's pixels
// and before RayCache::endFrame. Returns the rays traced. Deterministic: each
// texel is computed on its own, whatever the thread count.
RayCounts prefillCaches(RayCache& cache, std::span<const CacheWorker> workers, const TileKernel& kernel,
                        const Parallel& parallel);

}  // namespace raycache
