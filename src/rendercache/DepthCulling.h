#pragma once
// Depth culling of the enhanced Render Cache (Walter, Drettakis, Greenberg
// 2002): after reprojection, a surface seen from closer may not yet be dense
// enough to hide the samples behind it, which then show through its gaps. A
// reprojected sample is hidden when more of its 3x3 neighbours are markedly
// nearer (by `threshold` of its depth) than not, and at least three are: a
// sample at a straight silhouette, with three nearer neighbours and five
// not, is kept.
#include <cstdint>
#include <vector>

#include "core/Parallel.h"
#include "rendercache/PixelState.h"
#include "rendercache/PointImage.h"

namespace raycache {

// Whether the sample at pixel (x, y) of `image` (which must hold one; the
// margin must be at least 1) is hidden by the rule above.
inline bool hiddenByNearerNeighbours(const PointImage& image, int x, int y, float threshold) {
    // Compared as packed keys: no float decoding, empty pixels never nearer.
    const std::uint32_t nearerKey = PointImage::nearerThan(image.depthAt(x, y) * (1.0f - threshold));
    int nearer = 0, occupied = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const std::uint32_t key = image.keyAt(x + dx, y + dy);  // the margin is at least 1 pixel
            nearer += key <= nearerKey ? 1 : 0;
            occupied += key != PointImage::emptyKey() ? 1 : 0;
        }
    const int notNearer = occupied - 1 - nearer;  // the centre is occupied and not nearer than itself
    return nearer >= 3 && nearer > notNearer;
}

// Turns Reprojected pixels of `state` (width x height of `image`, whose
// margin must be at least 1) into Culled where the rule above holds;
// returns how many.
// `scratch`, when given, is reused from frame to frame (no allocation).
std::int64_t cullOccludedSamples(const PointImage& image, float threshold, std::vector<PixelState>& state,
                                 const Parallel& parallel, std::vector<unsigned char>* scratch = nullptr);

}  // namespace raycache
