#include "cache/DepthPyramid.h"

#include <algorithm>
#include <limits>

namespace raycache {

DepthPyramid::DepthPyramid(const CachingCube& cube) {
    const int n = cube.size();
    // Level 0 from the texels, each further level from the one below (4x4 blocks of blocks).
    for (int side = 4, shift = 2; side <= n; side *= 4, shift += 2) {
        Level level{side, shift, (n + side - 1) / side, {}};
        const auto perSide = static_cast<std::size_t>(level.blocksPerSide);
        level.depths.assign(6 * perSide * perSide, std::numeric_limits<float>::infinity());
        const Level* below = levels_.empty() ? nullptr : &levels_.back();
        for (int face = 0; face < 6; ++face) {
            const int cells = below ? below->blocksPerSide : n;  // what this level is made of, per side
            constexpr int cellSide = 4;                           // cells per block side
            for (int cy = 0; cy < cells; ++cy)
                for (int cx = 0; cx < cells; ++cx) {
                    const float d =
                        below ? below->depths[(static_cast<std::size_t>(face) * static_cast<std::size_t>(cells) +
                                               static_cast<std::size_t>(cy)) *
                                                  static_cast<std::size_t>(cells) +
                                              static_cast<std::size_t>(cx)]
                              : cube.depth(cubeTexelIndex(CubeTexel{static_cast<CubeFace>(face), cx, cy}, n));
                    float& m = level.depths[(static_cast<std::size_t>(face) * perSide +
                                             static_cast<std::size_t>(cy / cellSide)) *
                                                perSide +
                                            static_cast<std::size_t>(cx / cellSide)];
                    m = std::min(m, d);
                }
        }
        levels_.push_back(std::move(level));
    }
}

}  // namespace raycache
