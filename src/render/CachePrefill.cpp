#include "render/CachePrefill.h"

#include <vector>

#include "render/TileKernel.h"

namespace raycache {

RayCounts prefillCaches(RayCache& cache, std::span<const CacheWorker> workers, const TileKernel& kernel,
                        const Parallel& parallel) {
    std::vector<TileScratch> scratch(static_cast<std::size_t>(parallel.threadCount()));
    for (const int objectId : cache.objectsAwaitingPrefill(workers)) {
        const CachingCube& cube = cache.cube(objectId);
        std::vector<RayCache::PrefillTexel> texels(cube.texelCount());
        // The cube answers rays one bounce after the primary ray leaves a
        // surface, so its contents are shaded as depth-2 rays are.
        constexpr int kDepth = 2;
        // One face row of texels is one batch of the kernel, like a tile.
        const auto rowLength = static_cast<std::size_t>(cube.size());
        parallel.forEachIndex(6 * cube.size(), [&](int row, int worker) {
            std::vector<Ray> rays(rowLength);
            const std::size_t first = static_cast<std::size_t>(row) * rowLength;
            for (std::size_t i = 0; i < rowLength; ++i)
                rays[i] = Ray{cube.center(), cache.prefillDirection(objectId, static_cast<int>(first + i))};
            kernel.renderFromInside(objectId, rays, kDepth, std::span(texels).subspan(first, rowLength),
                                    scratch[static_cast<std::size_t>(worker)]);
        });
        cache.completePrefill(objectId, texels);
    }
    RayCounts total;
    for (const TileScratch& s : scratch) total += s.counts;
    return total;
}

}  // namespace raycache
