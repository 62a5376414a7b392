#pragma once
// Which structure answers primary rays and the shadow rays of primary hits
// (`--accel`, the scene key "accel"): Embree's BVH, or the per-frame grids
// of trace/grids/ (docs/grids.md). Secondary rays always use Embree. Here,
// below the tracer, because the scene format names it too: the scene file,
// the command line and the viewer read the names from here.
#include <array>

namespace raycache {

enum class Accelerator { Embree, Grids };
// Every accelerator, in the order messages, help texts and the viewer list them.
inline constexpr std::array kAccelerators{Accelerator::Embree, Accelerator::Grids};

constexpr const char* acceleratorName(Accelerator accelerator) {
    return accelerator == Accelerator::Grids ? "grids" : "embree";
}

}  // namespace raycache
