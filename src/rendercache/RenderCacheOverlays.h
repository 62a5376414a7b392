#pragma once
// What the viewer draws over a Render Cache frame: where each pixel came
// from (PixelState: reprojected, fresh, culled, filled, holes) and the
// priority and request maps of the frame.
#include <vector>

#include "rendercache/PixelState.h"
#include "rendercache/RequestMap.h"

namespace raycache {

struct RenderCacheOverlays {
    int width = 0, height = 0;
    std::vector<PixelState> state;  // per pixel, row-major
    RequestMap requests;            // this frame's camera (the predicted camera's requests are not shown)
};

}  // namespace raycache
