#pragma once
// Wall time since a steady-clock instant, in milliseconds: what every
// stage timing, progress line and benchmark reports.
#include <chrono>

namespace raycache {

inline double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace raycache
