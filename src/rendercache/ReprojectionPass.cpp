// RenderCachePipeline's first pass: every sample aged, evicted when too old,
// projected to the frame's camera (and the predicted next one); the nearer
// sample wins a pixel (rendercache/Reprojection.h).
#include "core/Elapsed.h"
#include "rendercache/RenderCacheFrameContext.h"

namespace raycache {

void RenderCachePipeline::reprojectSamples(FrameContext& f) {
    ReconstructionCounts& touched = f.touched;
    touched.width = f.width;
    touched.height = f.height;
    touched.pixelSlots = static_cast<std::int64_t>(f.imageSlots);
    touched.usedSlots = static_cast<std::int64_t>(pool_.used());

    const auto start = std::chrono::steady_clock::now();
    image_.reset(f.width, f.height, f.margin);
    f.reprojected = reproject(pool_, spare_, scene_, f.projection, f.rc.maxAge, image_, parallel_,
                              reprojectionScratch_, f.predicts ? &f.nextProjection : nullptr, &nextPixel_,
                              f.async ? f.async->ageStep : 1);
    std::swap(pool_, spare_);
    const ReprojectionCounts& reprojected = f.reprojected;
    f.stats.evicted = reprojected.evicted;
    f.stats.lost = reprojected.lost;
    f.stats.reprojectMs = millisecondsSince(start);
    touched.liveSamples = reprojected.live;
    touched.offered = reprojected.offered;
    touched.farOffers = reprojected.farOffers;
    touched.secondChances = reprojected.secondChances;
    touched.predicts = f.predicts;
    touched.placed = reprojected.placed;
    touched.moved = reprojected.moved;
    touched.reshadeCopied = reprojected.reshadeCopied;
    touched.texturingCopied = reprojected.texturingCopied;
}

}  // namespace raycache
