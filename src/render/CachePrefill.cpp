#include "render/CachePrefill.h"

#include <vector>

#include "render/TileKernel.h"

namespace raycache {

PrefillResult prefillCaches(RayCache& cache, std::span<const CacheWorker> workers, const TileKernel& kernel,
                            const Parallel& parallel, const ProcessGroup* group) {
    const int processes = group ? group->size() : 1;
    const int rank = group ? group->rank() : 0;
    PrefillResult result;
    const std::vector<RayCache::PrefillPiece> pieces = cache.planPrefill(workers);
    // Most frames pre-fill nothing (CCT never does): no scratch for them.
    if (pieces.empty()) return result;
    std::vector<TileScratch> scratch(static_cast<std::size_t>(parallel.threadCount()));
    for (const RayCache::PrefillPiece& piece : pieces) {
        const CachingCube& cube = cache.cube(piece.objectId);
        const auto rowLength = static_cast<std::size_t>(cube.size());
        std::vector<RayCache::PrefillTexel> texels(static_cast<std::size_t>(piece.rows) * rowLength);
        const auto rowSpan = [&](int row) {  // row of the piece, from 0
            return std::span(texels).subspan(static_cast<std::size_t>(row) * rowLength, rowLength);
        };
        // The cube answers rays one bounce after the primary ray leaves a
        // surface, so its contents are shaded as depth-2 rays are.
        constexpr int kDepth = 2;
        // One face row of texels is one batch of the kernel, like a tile;
        // this process traces the piece's rows rank, rank + N, ...
        const auto rowsOf = [&](int process) { return (piece.rows - process + processes - 1) / processes; };
        parallel.forEachIndex(rowsOf(rank), [&](int k, int worker) {
            const int row = rank + k * processes;
            std::vector<Ray> rays(rowLength);
            const std::size_t first = static_cast<std::size_t>(piece.firstRow + row) * rowLength;
            for (std::size_t i = 0; i < rowLength; ++i)
                rays[i] = Ray{cube.center(), cache.prefillDirection(piece.objectId, static_cast<int>(first + i))};
            kernel.renderFromInside(piece.objectId, rays, kDepth, rowSpan(row),
                                    scratch[static_cast<std::size_t>(worker)]);
        });
        if (processes > 1) {
            Bytes mine;
            for (int row = rank; row < piece.rows; row += processes)
                appendBytes(mine, std::span<const RayCache::PrefillTexel>(rowSpan(row)));
            GatheredBytes all;
            group->allGather(mine, all);
            for (int r = 0; r < processes; ++r) {
                result.exchangedBytes += all.of(static_cast<std::size_t>(r)).size();
                if (r == rank) continue;
                ByteReader reader(all.of(static_cast<std::size_t>(r)));
                for (int row = r; row < piece.rows; row += processes) reader.readInto(rowSpan(row));
            }
        }
        cache.addPrefillRows(piece.objectId, piece.firstRow, texels);
    }
    for (const TileScratch& s : scratch) result.rays += s.counts;
    return result;
}

}  // namespace raycache
