#include "core/LaneInstructionSet.h"

#include "core/LaneLevels.h"

#include <cstdlib>
#include <string_view>

namespace raycache {

namespace {

// The x86-64 levels of core/LaneLevels.h. GCC tests a level by name; clang
// 14 (the fuzz build) knows no level names, so there the level's
// distinguishing features stand for it.
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

// The widest level this processor runs (decided once per process), or
// Baseline where the build has one level.
LaneLevel widestLaneLevel() {
#if defined(RAYCACHE_BASELINE_LANES) || !defined(__x86_64__)
    return LaneLevel::Baseline;
#else
    static const LaneLevel widest = [] {
        __builtin_cpu_init();
        return cpuHasLevel4() ? LaneLevel::Avx512 : cpuHasLevel3() ? LaneLevel::Avx2 : LaneLevel::Baseline;
    }();
    return widest;
#endif
}

}  // namespace

std::string laneInstructionSet() {
#if defined(RAYCACHE_BASELINE_LANES)
    return "x86-64 (baseline; built with RAYCACHE_BASELINE_LANES)";
#elif defined(__x86_64__)
    const LaneLevel level = widestLaneLevel();
    const std::string widest = level == LaneLevel::Avx512 ? "x86-64-v4 (AVX-512)"
                               : level == LaneLevel::Avx2 ? "x86-64-v3 (AVX2)"
                                                          : "x86-64 (baseline)";
    if (std::getenv("RAYCACHE_LANES"))
        return widest + "; lanes " + laneLevelName(laneLevel()) + " (RAYCACHE_LANES)";
    return widest;
#else
    return "the target's baseline (no lane levels off x86-64)";
#endif
}

LaneLevel laneLevel() {
    static const LaneLevel level = narrowedLaneLevel().value_or(widestLaneLevel());
    return level;
}

std::optional<LaneLevel> narrowedLaneLevel() {
#if defined(RAYCACHE_BASELINE_LANES) || !defined(__x86_64__)
    return std::nullopt;
#else
    // RAYCACHE_LANES narrows the level (never widens it past the processor):
    // how the tests compare every level's bits on one machine.
    static const std::optional<LaneLevel> narrowed = []() -> std::optional<LaneLevel> {
        const std::optional<LaneLevel> asked = parseLaneLevel(std::getenv("RAYCACHE_LANES"));
        if (asked && *asked < widestLaneLevel()) return asked;
        return std::nullopt;
    }();
    return narrowed;
#endif
}

std::optional<LaneLevel> parseLaneLevel(const char* name) {
    if (!name) return std::nullopt;
    const std::string_view n(name);
    if (n == "avx512") return LaneLevel::Avx512;
    if (n == "avx2") return LaneLevel::Avx2;
    if (n == "baseline") return LaneLevel::Baseline;
    return std::nullopt;
}

const char* laneLevelName(LaneLevel level) {
    switch (level) {
    case LaneLevel::Avx512: return "avx512";
    case LaneLevel::Avx2: return "avx2";
    case LaneLevel::Baseline: return "baseline";
    }
    return "baseline";
}

bool builtWithBaselineLanes() {
#if defined(RAYCACHE_BASELINE_LANES)
    return true;
#else
    return false;
#endif
}

}  // namespace raycache
