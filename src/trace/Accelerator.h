#pragma once
// Which structure answers primary rays and the shadow rays of primary hits
// (`--accel`, the scene key "accel"): Embree's BVH, or the per-frame grids
// of trace/grids/ (docs/grids.md). Secondary rays always use Embree.
#include <optional>
#include <string>

namespace raycache {

enum class Accelerator { Embree, Grids };

inline const char* acceleratorName(Accelerator accelerator) {
    return accelerator == Accelerator::Grids ? "grids" : "embree";
}

// "embree" or "grids"; nothing for any other name.
inline std::optional<Accelerator> parseAccelerator(const std::string& name) {
    if (name == "embree") return Accelerator::Embree;
    if (name == "grids") return Accelerator::Grids;
    return std::nullopt;
}

}  // namespace raycache
