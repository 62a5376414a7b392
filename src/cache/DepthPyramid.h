#pragma once
// Minimum stored depth over square blocks of a CDCT cube's faces, at block
// sides 4, 16, 64, ... texels: where a ray stays nearer to the centre than
// every depth of a block, it cannot meet that block's surface, so the
// improved search crosses the block in one step instead of texel by texel
// (the "maximum mipmap" idea of relief mapping, on a cube).
#include <vector>

#include "cache/CachingCube.h"

namespace raycache {

class DepthPyramid {
public:
    // From the cube's depths as they stand (invalid texels count as depth -1,
    // so blocks holding one are never skipped).
    explicit DepthPyramid(const CachingCube& cube);

    int levelCount() const { return static_cast<int>(levels_.size()); }
    // Side of level `level`'s blocks in texels: 4^(level + 1).
    int blockSide(int level) const { return levels_[static_cast<std::size_t>(level)].blockSide; }
    // Minimum depth of the block at level `level` holding texel (x, y) of `face`.
    float minDepth(int level, int face, int x, int y) const {
        const Level& l = levels_[static_cast<std::size_t>(level)];
        const int bx = x >> l.shift, by = y >> l.shift;  // blockSide = 1 << shift
        return l.depths[(static_cast<std::size_t>(face) * static_cast<std::size_t>(l.blocksPerSide) +
                          static_cast<std::size_t>(by)) *
                             static_cast<std::size_t>(l.blocksPerSide) +
                         static_cast<std::size_t>(bx)];
    }

private:
    struct Level {
        int blockSide;
        int shift;  // log2(blockSide)
        int blocksPerSide;
        std::vector<float> depths;  // face-major, row-major blocks
    };
    std::vector<Level> levels_;
};

}  // namespace raycache
