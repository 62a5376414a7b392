#include "viewer/RenderCacheOverlayImage.h"

#include <algorithm>

#include "viewer/OverlayBlend.h"

namespace raycache {

void paintRenderCacheOverlay(const RenderCacheOverlays& o, RenderCacheOverlay which, std::vector<std::uint8_t>& rgba) {
    const auto pixels = static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height);
    if (which == RenderCacheOverlay::None || rgba.size() != pixels * 4 || o.state.size() != pixels) return;
    if (which == RenderCacheOverlay::Sources) {
        for (std::size_t i = 0; i < pixels; ++i) {
            std::uint8_t* p = &rgba[i * 4];
            switch (o.state[i]) {
                case PixelState::Fresh: blendOverlay(p, 0, 255, 0, 160); break;
                case PixelState::Culled: blendOverlay(p, 255, 0, 255, 200); break;
                case PixelState::Filled3x3: blendOverlay(p, 255, 255, 0, 200); break;
                case PixelState::Filled7x7: blendOverlay(p, 255, 128, 0, 220); break;
                case PixelState::Unfilled:
                case PixelState::Hole: blendOverlay(p, 255, 0, 0, 256); break;
                case PixelState::Reprojected: break;
            }
        }
        return;
    }
    const RequestMap& m = o.requests;
    if (!m.tilePriority.empty()) {
        const float top = std::max(1e-6f, *std::max_element(m.tilePriority.begin(), m.tilePriority.end()));
        for (int y = 0; y < o.height; ++y)
            for (int x = 0; x < o.width; ++x) {
                const auto t = static_cast<std::size_t>((y / m.tileSize) * m.tilesX + x / m.tileSize);
                const int alpha = static_cast<int>(200.0f * m.tilePriority[t] / top);
                const std::size_t i =
                    static_cast<std::size_t>(y) * static_cast<std::size_t>(o.width) + static_cast<std::size_t>(x);
                blendOverlay(&rgba[i * 4], 0, 64, 255, alpha);
            }
    }
    for (const PixelCoord& p : m.pixels) {
        std::uint8_t* px = &rgba[(static_cast<std::size_t>(p.y) * static_cast<std::size_t>(o.width) + static_cast<std::size_t>(p.x)) * 4];
        px[0] = px[1] = px[2] = 255;
    }
}

}  // namespace raycache
