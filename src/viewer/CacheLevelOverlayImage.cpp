#include "viewer/CacheLevelOverlayImage.h"

#include "viewer/OverlayBlend.h"

namespace raycache {

namespace {

// Index: the record value + 2 (CacheLevelImage::Counts' order). Green for the
// finest level, then warmer, then cold colours for levels few scenes reach.
constexpr std::array<std::array<std::uint8_t, 3>, kMaxCubeLevels + 2> kColors = {{
    {128, 128, 128},  // no caching ray
    {255, 0, 0},      // traced
    {0, 255, 0},      // level 0
    {255, 255, 0},    // level 1
    {255, 128, 0},    // level 2
    {255, 0, 255},    // level 3
    {0, 96, 255},     // level 4
    {0, 255, 255},    // level 5
    {255, 255, 255},  // level 6
    {128, 0, 255},    // level 7
}};

}  // namespace

std::array<std::uint8_t, 3> cacheLevelColor(std::int8_t value) {
    return kColors[static_cast<std::size_t>(value + 2)];
}

void paintCacheLevelOverlay(const CacheLevelImage& levels, std::vector<std::uint8_t>& rgba) {
    const std::vector<std::int8_t>& values = levels.values();
    if (rgba.size() != values.size() * 4) return;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const std::array<std::uint8_t, 3>& c = kColors[static_cast<std::size_t>(values[i] + 2)];
        blendOverlay(&rgba[i * 4], c[0], c[1], c[2], kCacheLevelOverlayAlpha);
    }
}

}  // namespace raycache
