#pragma once
// The viewer's Render Cache overlays, painted over the displayed frame:
// where each pixel came from, or the request map of the frame.
#include <cstdint>
#include <vector>

#include "rendercache/RenderCacheOverlays.h"

namespace raycache {

enum class RenderCacheOverlay : int {
    None = 0,
    Sources,   // fresh green, culled magenta, 3x3-filled yellow, 7x7-filled orange, unfilled red; reprojected as is
    Requests,  // tiles tinted blue by priority, requested pixels white
};

// Blends the overlay into `rgba` (8-bit RGBA, the overlays' size; nothing
// happens when the sizes differ, e.g. the frame after a resize).
void paintRenderCacheOverlay(const RenderCacheOverlays& overlays, RenderCacheOverlay which, std::vector<std::uint8_t>& rgba);

}  // namespace raycache
