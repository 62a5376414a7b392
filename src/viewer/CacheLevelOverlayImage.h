#pragma once
// The viewer's "cube level per pixel" overlay, painted over the displayed
// frame: per pixel, what the cache did for its rays leaving caching objects
// (render/CacheLevelImage.h says which lookup a pixel keeps). The panel's
// legend uses the same colours.
#include <array>
#include <cstdint>
#include <vector>

#include "render/CacheLevelImage.h"

namespace raycache {

// How strongly the overlay's colours cover the frame, of 256: the image
// stays readable underneath.
inline constexpr int kCacheLevelOverlayAlpha = 160;

// The colour (8-bit RGB) of record value `value`: no caching ray grey, traced
// red, level 0 (the finest) green, then level 1 yellow, 2 orange, 3 magenta,
// 4 blue, 5 cyan, 6 white, 7 violet.
std::array<std::uint8_t, 3> cacheLevelColor(std::int8_t value);

// Blends each pixel's colour into `rgba` (8-bit RGBA, the record's size;
// nothing happens when the sizes differ, e.g. the frame after a resize).
void paintCacheLevelOverlay(const CacheLevelImage& levels, std::vector<std::uint8_t>& rgba);

}  // namespace raycache
