#include "rendercache/DepthCulling.h"

namespace raycache {

std::int64_t cullOccludedSamples(const PointImage& image, float threshold, std::vector<PixelState>& state,
                                 const Parallel& parallel, std::vector<unsigned char>* scratch) {
    const int width = image.width(), height = image.height();
    std::vector<std::int64_t> perRow(static_cast<std::size_t>(height), 0);
    // Decide from the depths alone, then write, so a row's decision never
    // sees a neighbour row's result.
    std::vector<unsigned char> ownScratch;
    std::vector<unsigned char>& hide = scratch ? *scratch : ownScratch;
    hide.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
    parallel.forEachIndex(height, [&](int y, int) {
        std::int64_t rowCulled = 0;  // written once: neighbouring rows' counters share a cache line
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                  static_cast<std::size_t>(x);
            if (state[i] != PixelState::Reprojected) continue;
            // Compared as packed keys: no float decoding, empty pixels never nearer.
            const std::uint64_t nearerKey = PointImage::nearerThan(image.depthAt(x, y) * (1.0f - threshold));
            int nearer = 0, occupied = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const std::uint64_t key = image.keyAt(x + dx, y + dy);  // the margin is at least 1 pixel
                    nearer += key <= nearerKey ? 1 : 0;
                    occupied += key != PointImage::emptyKey() ? 1 : 0;
                }
            const int notNearer = occupied - 1 - nearer;  // the centre is occupied and not nearer than itself
            if (nearer >= 3 && nearer > notNearer) {
                hide[i] = 1;
                ++rowCulled;
            }
        }
        perRow[static_cast<std::size_t>(y)] = rowCulled;
    });
    parallel.forEachIndex(height, [&](int y, int) {
        const auto row = static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
        for (std::size_t i = row; i < row + static_cast<std::size_t>(width); ++i)
            if (hide[i]) state[i] = PixelState::Culled;
    });
    std::int64_t culled = 0;
    for (std::int64_t c : perRow) culled += c;
    return culled;
}

}  // namespace raycache
