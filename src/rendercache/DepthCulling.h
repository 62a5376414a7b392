#pragma once
// Depth culling of the enhanced Render Cache (Walter, Drettakis, Greenberg
// 2002): after reprojection, a surface seen from closer may not yet be dense
// enough to hide the samples behind it, which then show through its gaps. A
// reprojected sample is hidden when more of its 3x3 neighbours are markedly
// nearer (by `threshold` of its depth) than not, and at least three are: a
// sample at a straight silhouette, with three nearer neighbours and five
// not, is kept.
#include <cstdint>

#include "rendercache/PointImage.h"

namespace raycache {

// The rule above on a sample's key `row[0]` and its neighbours' keys:
// `above`, `row` and `below` point at its column in three consecutive rows
// of a PointImage's keys (PointImage::keyData()), each readable one pixel
// to either side.
inline bool hiddenByNearerKeys(const std::uint32_t* above, const std::uint32_t* row, const std::uint32_t* below,
                               float threshold) {
    // Compared as packed keys: no float decoding, empty pixels never nearer.
    const std::uint32_t nearerKey = PointImage::nearerThan(PointImage::depthOf(row[0]) * (1.0f - threshold));
    int nearer = 0, occupied = 0;
    for (const std::uint32_t* keys : {above, row, below})
        for (int dx = -1; dx <= 1; ++dx) {
            const std::uint32_t key = keys[dx];
            nearer += key <= nearerKey ? 1 : 0;
            occupied += key != PointImage::emptyKey() ? 1 : 0;
        }
    const int notNearer = occupied - 1 - nearer;  // the centre is occupied and not nearer than itself
    return nearer >= 3 && nearer > notNearer;
}

// hidden[x] = hiddenByNearerKeys(above + x, row + x, below + x, threshold)
// for x in [0, count), a register of pixels at a time (the holes pass of
// RenderCachePipeline decides a whole row before it classifies it: a
// pixel's nine keys one by one cost ~70 instructions); the same decisions bit
// for bit. Each row is readable one pixel to either side, as above.
void hiddenByNearerKeysRow(const std::uint32_t* above, const std::uint32_t* row, const std::uint32_t* below, int count,
                           float threshold, unsigned char* hidden);

}  // namespace raycache
