#pragma once
// The centre rays of one image row, made sixteen at a time
// (CameraRays::rowOfRays: the same bits as CameraRays::ray) and only for
// the blocks of sixteen pixels where a pass asks for one: the Render
// Cache's passes need the rays of some pixels of a row (textured samples,
// filled holes), and one at a time each cost a square root and a division.
#include <algorithm>

#include "core/FloatLanes.h"
#include "render/CameraRays.h"

namespace raycache {

class RowRays {
public:
    // Row `y` of `rays`' width x height image.
    RowRays(const CameraRays& rays, int width, int y) : rays_(rays), width_(width), y_(y) {}

    // rays.ray(x, y), for 0 <= x < width.
    const Ray& at(int x) {
        const int block = x - x % kFloatLanes;
        if (block != block_) {
            rays_.rowOfRays(block, y_, std::min(kFloatLanes, width_ - block), blockRays_);
            block_ = block;
        }
        return blockRays_[x - block];
    }

private:
    const CameraRays& rays_;
    int width_, y_;
    int block_ = -1;  // the first pixel of the block in blockRays_
    Ray blockRays_[kFloatLanes];
};

}  // namespace raycache
