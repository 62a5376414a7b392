#include "core/LaneInstructionSet.h"

#include "core/LaneLevels.h"

namespace raycache {

namespace {

// The levels of core/LaneClones.h's clones, as the loader's resolver tests
// them. GCC tests a level by name; clang 14 (the fuzz build) knows no level
// names, so there the level's distinguishing features stand for it.
[[maybe_unused]] bool cpuHasLevel4() {
#if defined(__clang__)
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx2");
#else
    return __builtin_cpu_supports("x86-64-v4");
#endif
}

[[maybe_unused]] bool cpuHasLevel3() {
#if defined(__clang__)
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
           __builtin_cpu_supports("bmi2");
#else
    return __builtin_cpu_supports("x86-64-v3");
#endif
}

}  // namespace

std::string laneInstructionSet() {
#if defined(RAYCACHE_BASELINE_LANES)
    return "x86-64 (baseline; built with RAYCACHE_BASELINE_LANES)";
#elif defined(__x86_64__)
    __builtin_cpu_init();
    if (cpuHasLevel4()) return "x86-64-v4 (AVX-512)";
    if (cpuHasLevel3()) return "x86-64-v3 (AVX2)";
    return "x86-64 (baseline)";
#else
    return "the target's baseline (no clones off x86-64)";
#endif
}

LaneLevel laneLevel() {
#if defined(RAYCACHE_BASELINE_LANES) || !defined(__x86_64__)
    return LaneLevel::Baseline;
#else
    static const LaneLevel level = [] {
        __builtin_cpu_init();
        if (cpuHasLevel4()) return LaneLevel::Avx512;
        if (cpuHasLevel3()) return LaneLevel::Avx2;
        return LaneLevel::Baseline;
    }();
    return level;
#endif
}

bool builtWithBaselineLanes() {
#if defined(RAYCACHE_BASELINE_LANES)
    return true;
#else
    return false;
#endif
}

}  // namespace raycache
