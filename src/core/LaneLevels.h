#pragma once
// Lane code compiled once per x86-64 level, for files whose lanes combine
// masks (core/FloatLanes.h). GCC's target_clones (core/LaneClones.h) lowers
// a function's vector operations for the baseline target before it makes
// the clones, and GCC 12 then turns a 16-lane mask's &, | and ~ into one
// scalar compare per lane even in the AVX-512 clone (seen in perf: half of
// the sphere callback's time). So such a file keeps its lane functions in a
// .inc file that it includes three times, inside namespaces avx512, avx2 and
// baseline, the first two under `#pragma GCC target` for their level, and
// calls them through RAYCACHE_LANE_DISPATCH. Every copy is the same source,
// so the same IEEE operations: the same bits on every level.
//
//   namespace raycache {
//   #define RAYCACHE_LANE_KERNELS "render/FileKernels.inc"  // namespace RAYCACHE_LANE_LEVEL { ... }
//   #include "core/LaneLevelsInclude.h"                       // the three copies
//   void f(...) { RAYCACHE_LANE_DISPATCH(fLanes, ...); }
//
// A build with RAYCACHE_BASELINE_LANES (the sanitizer and fuzz presets; see
// core/LaneClones.h) includes the baseline copy alone.
#include <optional>

namespace raycache {

// Ordered: a wider level compares greater.
enum class LaneLevel { Baseline, Avx2, Avx512 };

// The widest level this processor runs (decided once per process), or
// Baseline in a build with RAYCACHE_BASELINE_LANES. The environment
// variable RAYCACHE_LANES (avx512, avx2 or baseline) narrows it, never past
// what the processor runs: the images are the same at every level, and
// tests/app/LaneLevelsCliTest.cpp holds the program to that.
LaneLevel laneLevel();
// "avx512", "avx2", "baseline" and back (nothing for another name or null).
std::optional<LaneLevel> parseLaneLevel(const char* name);
const char* laneLevelName(LaneLevel level);

}  // namespace raycache

#if defined(RAYCACHE_BASELINE_LANES)
#define RAYCACHE_LANE_DISPATCH(function, ...) return baseline::function(__VA_ARGS__)
#else
#define RAYCACHE_LANE_DISPATCH(function, ...)                                      \
    switch (::raycache::laneLevel()) {                                            \
    case ::raycache::LaneLevel::Avx512: return avx512::function(__VA_ARGS__);     \
    case ::raycache::LaneLevel::Avx2: return avx2::function(__VA_ARGS__);         \
    case ::raycache::LaneLevel::Baseline: break;                                  \
    }                                                                             \
    return baseline::function(__VA_ARGS__)
#endif
