#pragma once
// What the tile kernel (render/TileKernel.h) gathers for the visible-surface
// fill (render/VisibleSurfaceFill.h): per root whose first hit may fill a
// cube, the root and the hit point; once the tile is resolved, the points
// with their pixels' colours, and the fill's own buffers.
#include <vector>

#include "core/Vec3.h"
#include "render/VisibleSurfaceFill.h"

namespace raycache {

struct TileVisibleFill {
    std::vector<int> roots;
    std::vector<Vec3> positions;
    std::vector<VisiblePoint> points;
    VisibleFillScratch scratch;
};

}  // namespace raycache
