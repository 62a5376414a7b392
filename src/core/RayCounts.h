#pragma once
#include <cstdint>

namespace raycache {

// Rays traced, by kind. Summed per worker and merged at the end of a frame.
struct RayCounts {
    std::uint64_t primary = 0;
    std::uint64_t shadow = 0;
    std::uint64_t reflection = 0;
    std::uint64_t refraction = 0;
    std::uint64_t prefill = 0;  // improved CDCT: rays from a cube's centre filling it
    std::uint64_t fill = 0;     // visibility rays from caching objects to surfaces the camera saw (visible-surface fill)

    std::uint64_t total() const { return primary + shadow + reflection + refraction + prefill + fill; }
    RayCounts& operator+=(const RayCounts& o) {
        primary += o.primary;
        shadow += o.shadow;
        reflection += o.reflection;
        refraction += o.refraction;
        prefill += o.prefill;
        fill += o.fill;
        return *this;
    }
};

}  // namespace raycache
