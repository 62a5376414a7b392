#pragma once
// Which reprojected samples a Render Cache frame reshades
// (RenderCacheSettings::reshadeInterval). Reshading a mirror, glass or
// highlight sample from the new eye costs a shading and, through the caching
// cubes, a lookup per sample; on scenes full of mirrors it is a large share
// of a display frame. With an interval N above 1, a moving frame reshades the
// samples whose pixel (x, y) satisfies (x + 3y + round) mod N = 0, a pattern
// that shifts each moving frame so that every sample takes its turn once in N
// frames, and marks the rest as shaded from an older eye; the first frame
// whose camera did not move reshades those. One rule, asked by the passes
// that count, replace and reshade samples, so that their counts agree.
#include <cstdint>

#include "rendercache/SamplePool.h"

namespace raycache {

struct ReshadeSelection {
    bool moved = false;        // the camera differs from the last frame's
    int interval = 1;          // RenderCacheSettings::reshadeInterval
    std::uint32_t round = 0;   // moving frames before this one

    // Whether the frame reshades anything: a moving frame, or a still one
    // that may find samples shaded from an older eye.
    bool any() const { return moved || interval > 1; }

    bool inTurn(int x, int y) const {
        const auto position = static_cast<std::uint32_t>(x) + 3u * static_cast<std::uint32_t>(y) + round;
        return position % static_cast<std::uint32_t>(interval) == 0;
    }

    // A reprojected sample at pixel (x, y) is reshaded this frame.
    bool chooses(const SampleLook& look, int x, int y) const {
        if (look.viewDependent == 0) return false;
        if (!moved) return (look.viewDependent & kShadedFromAnOlderEye) != 0;
        return interval == 1 || inTurn(x, y);
    }
};

}  // namespace raycache
