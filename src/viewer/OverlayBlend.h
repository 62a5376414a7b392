#pragma once
// How the viewer's overlays tint a displayed pixel: the 8-bit colour mixed
// into the pixel's RGB with weight alpha256 / 256 (256: the colour alone).
#include <cstdint>

namespace raycache {

inline void blendOverlay(std::uint8_t* pixel, int r, int g, int b, int alpha256) {
    const int keep = 256 - alpha256;
    pixel[0] = static_cast<std::uint8_t>((pixel[0] * keep + r * alpha256) >> 8);
    pixel[1] = static_cast<std::uint8_t>((pixel[1] * keep + g * alpha256) >> 8);
    pixel[2] = static_cast<std::uint8_t>((pixel[2] * keep + b * alpha256) >> 8);
}

}  // namespace raycache
