#pragma once
// Every lane loop is compiled once per x86-64 level and chosen at run time
// by laneLevel(); docs/architecture.md ("Lane levels") says how and why. A
// file keeps its lane functions in a .inc file and calls them through
// RAYCACHE_LANE_DISPATCH:
//
//   namespace raycache {
//   #define RAYCACHE_LANE_KERNELS "render/FileKernels.inc"  // namespace RAYCACHE_LANE_LEVEL { ... }
//   #include "core/LaneLevelsInclude.h"                       // the copies
//   void f(...) { RAYCACHE_LANE_DISPATCH(fLanes, ...); }
//
// Kernels with no AVX-512 copy (RAYCACHE_LANE_LEVELS_UP_TO_AVX2 before the
// include) are called with RAYCACHE_LANE_DISPATCH_UP_TO_AVX2, which runs the
// avx2 copy at the avx512 level.
#include <optional>

namespace raycache {

// Ordered: a wider level compares greater.
enum class LaneLevel { Baseline, Avx2, Avx512 };

// The widest level this processor runs (decided once per process), or
// Baseline in a build with RAYCACHE_BASELINE_LANES. The environment
// variable RAYCACHE_LANES (avx512, avx2 or baseline) narrows it, never past
// what the processor runs: the lane code's images are the same at every
// level (with Embree held at one level: trace/EmbreeDeviceConfig.h), and
// tests/app/LaneLevelsCliTest.cpp holds the program to that.
LaneLevel laneLevel();
// The level RAYCACHE_LANES narrowed laneLevel() to, when it is below what
// the processor runs: the run then stands for a processor without the wider
// levels, and the tracer asks Embree for no wider instructions either
// (trace/EmbreeDeviceConfig.h). Nothing when unnarrowed, and always nothing
// in a build with RAYCACHE_BASELINE_LANES, which has one level.
std::optional<LaneLevel> narrowedLaneLevel();
// "avx512", "avx2", "baseline" and back (nothing for another name or null).
std::optional<LaneLevel> parseLaneLevel(const char* name);
const char* laneLevelName(LaneLevel level);

}  // namespace raycache

#if defined(RAYCACHE_BASELINE_LANES)
#define RAYCACHE_LANE_DISPATCH(function, ...) return baseline::function(__VA_ARGS__)
#define RAYCACHE_LANE_DISPATCH_UP_TO_AVX2(function, ...) return baseline::function(__VA_ARGS__)
#else
#define RAYCACHE_LANE_DISPATCH(function, ...)                                      \
    switch (::raycache::laneLevel()) {                                            \
    case ::raycache::LaneLevel::Avx512: return avx512::function(__VA_ARGS__);     \
    case ::raycache::LaneLevel::Avx2: return avx2::function(__VA_ARGS__);         \
    case ::raycache::LaneLevel::Baseline: break;                                  \
    }                                                                             \
    return baseline::function(__VA_ARGS__)
#define RAYCACHE_LANE_DISPATCH_UP_TO_AVX2(function, ...)                            \
    if (::raycache::laneLevel() != ::raycache::LaneLevel::Baseline) return avx2::function(__VA_ARGS__); \
    return baseline::function(__VA_ARGS__)
#endif
