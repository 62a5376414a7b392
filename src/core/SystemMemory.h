#pragma once
// How much memory this machine has, for defaults that scale with it (the
// caching cubes' budget, RenderJob).
#include <cstddef>

namespace raycache {

// Physical memory in bytes (0 if the system does not say).
std::size_t physicalMemoryBytes();

}  // namespace raycache
