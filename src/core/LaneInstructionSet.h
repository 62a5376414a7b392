#pragma once
// Which instruction set the lane code (core/LaneClones.h) runs on this CPU.
#include <string>

namespace raycache {

// The widest clone the program loader picks here for the sixteen-float lanes:
// "x86-64-v4 (AVX-512)", "x86-64-v3 (AVX2)" or "x86-64 (baseline)"; the
// eight-float lanes stop at x86-64-v3. A build with RAYCACHE_BASELINE_LANES
// has the baseline clone alone, and says so.
std::string laneInstructionSet();

// Whether this build was compiled with RAYCACHE_BASELINE_LANES.
bool builtWithBaselineLanes();

}  // namespace raycache
