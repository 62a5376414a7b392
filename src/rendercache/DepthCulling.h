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

// Turns Reprojected pixels of `state` (width x height of `image`, whose
// margin must be at least 1) into Culled where the rule above holds;
// returns how many.
// `scratch`, when given, is reused from frame to frame (no allocation).
std::int64_t cullOccludedSamples(const PointImage& image, float threshold, std::vector<PixelState>& state,
                                 const Parallel& parallel, std::vector<unsigned char>* scratch = nullptr);

}  // namespace raycache
