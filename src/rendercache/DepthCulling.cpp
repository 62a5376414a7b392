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
            if (hiddenByNearerNeighbours(image, x, y, threshold)) {
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
