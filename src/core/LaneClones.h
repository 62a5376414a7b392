#pragma once
// The grids' lane loops are compiled twice, for AVX2 (x86-64-v3) and for
// baseline x86-64, and the CPU picks one when the program loads. Both must
// give the same bits (cmake/Warnings.cmake keeps FMAs out). A machine with
// AVX2 only ever runs the first, so a build with RAYCACHE_BASELINE_LANES
// (the CMake option of that name; the sanitizer and fuzz presets set it)
// compiles the baseline one alone: the test suite then runs each clone in one
// of its builds. The sanitizer builds need it anyway: the resolver that picks
// a clone runs while the program is being loaded, before the sanitizer's
// runtime is ready, and ThreadSanitizer's instrumentation in it crashes. The attribute must be on a function's first declaration (clang).
// RAYCACHE_WIDE_LANE_CLONES is the same for sixteen-float lanes
// (core/FloatLanes.h), which AVX-512 (x86-64-v4) computes in one instruction.
#if defined(RAYCACHE_BASELINE_LANES)
#define RAYCACHE_LANE_CLONES
#define RAYCACHE_WIDE_LANE_CLONES
#else
#define RAYCACHE_LANE_CLONES [[gnu::target_clones("arch=x86-64-v3", "default")]]
#define RAYCACHE_WIDE_LANE_CLONES [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#endif
