#pragma once
// Which structure answers primary rays and the shadow rays of primary hits
// (`--accel`, the scene key "accel"): Embree's BVH, or the per-frame grids
// of trace/grids/ (docs/grids.md). Secondary rays always use Embree.
#include <array>
#include <optional>
#include <string>

namespace raycache {

enum class Accelerator { Embree, Grids };
// Every accelerator, in the order messages, help texts and the viewer list them.
inline constexpr std::array kAccelerators{Accelerator::Embree, Accelerator::Grids};

inline const char* acceleratorName(Accelerator accelerator) {
    return accelerator == Accelerator::Grids ? "grids" : "embree";
}

// "embree" or "grids"; nothing for any other name.
inline std::optional<Accelerator> parseAccelerator(const std::string& name) {
    for (const Accelerator accelerator : kAccelerators)
        if (name == acceleratorName(accelerator)) return accelerator;
    return std::nullopt;
}

}  // namespace raycache
