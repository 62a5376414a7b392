#pragma once
// Which instruction set the lane code (core/LaneLevels.h) runs on this CPU.
#include <string>

namespace raycache {

// The widest level this processor runs: "x86-64-v4 (AVX-512)", "x86-64-v3
// (AVX2)" or "x86-64 (baseline)", and the level laneLevel() chose when
// RAYCACHE_LANES narrows it. A build with RAYCACHE_BASELINE_LANES has the
// baseline copy alone, and says so.
std::string laneInstructionSet();

// Whether this build was compiled with RAYCACHE_BASELINE_LANES.
bool builtWithBaselineLanes();

}  // namespace raycache
