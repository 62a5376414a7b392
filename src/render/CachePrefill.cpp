#include "render/CachePrefill.h"

#include <vector>

namespace raycache {

RayCounts prefillCaches(RayCache& cache, std::span<const CacheWorker> workers, const WhittedIntegrator& integrator,
                        const Parallel& parallel) {
    std::vector<RayCounts> counts(static_cast<std::size_t>(parallel.threadCount()));
    for (const int objectId : cache.objectsAwaitingPrefill(workers)) {
        const CachingCube& cube = cache.cube(objectId);
        std::vector<RayCache::PrefillTexel> texels(cube.texelCount());
        // The cube answers rays one bounce after the primary ray leaves a
        // surface, so its contents are shaded as depth-2 rays are.
        constexpr int kDepth = 2;
        const int rowLength = cube.size();
        parallel.forEachIndex(6 * cube.size(), [&](int row, int worker) {
            PathContext path{counts[static_cast<std::size_t>(worker)], nullptr};
            for (int i = row * rowLength; i < (row + 1) * rowLength; ++i) {
                const Ray ray{cube.center(), cache.prefillDirection(objectId, i)};
                RayCache::PrefillTexel& t = texels[static_cast<std::size_t>(i)];
                t.color = integrator.traceFromInside(objectId, ray, kDepth, path, t.hitDistance);
            }
        });
        cache.completePrefill(objectId, texels);
    }
    RayCounts total;
    for (const RayCounts& c : counts) total += c;
    return total;
}

}  // namespace raycache
