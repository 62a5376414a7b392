#pragma once
// The centre rays of one image row, made sixteen at a time
// (CameraRays::rowOfRays: the same bits as CameraRays::ray) and only for
// the blocks of sixteen pixels where a pass asks for one: the Render
// Cache's passes need the rays of some pixels of a row (textured samples),
// and one at a time each cost a square root and a division.
#include "core/FloatLanes.h"
#include "render/CameraRays.h"
#include "trace/RayPacket.h"

namespace raycache {

class RowRays {
public:
    // Row `y` of `rays`' image.
    RowRays(const CameraRays& rays, int y) : rays_(rays), y_(y) {}

    // rays.ray(x, y), for x >= 0.
    Ray at(int x) {
        const RayLanes16& lanes = block(x);
        return laneRay(lanes, x - block_);
    }
    // The rays of the block of sixteen pixels that holds pixel x, lane k
    // that of pixel x - x % 16 + k (past the row's end too).
    const RayLanes16& block(int x) {
        const int first = x - x % kFloatLanes;
        if (first != block_) {
            rays_.rowOfRays(first, y_, blockRays_);
            block_ = first;
        }
        return blockRays_;
    }

private:
    const CameraRays& rays_;
    int y_;
    int block_ = -1;  // the first pixel of the block in blockRays_
    RayLanes16 blockRays_;
};

}  // namespace raycache
