#pragma once
// The configuration string every Embree device of the tracer is created with,
// and what it lets Embree use, for reports.
#include <string>

namespace raycache {

// "threads=N" when the build threads are bounded (0: Embree's own choice),
// and "max_isa=" a level when Embree's instructions are bounded:
// - by RAYCACHE_LANES, when it narrows the lane level below the processor's
//   (core/LaneLevels.h): such a run stands for a processor without the wider
//   instructions, where Embree could not use them either. Without the bound
//   an avx2 run would trace with AVX-512 and shade with AVX2, and its timings
//   would describe no real processor;
// - by RAYCACHE_EMBREE_ISA (avx512, avx2 or baseline), which bounds Embree
//   alone, apart from the lanes: Embree's kernels at different widths do not
//   always agree on a ray that grazes an edge (it hits in one, misses in the
//   other), so the tests that compare the lane code's levels pin Embree to
//   one level for all of them.
std::string embreeDeviceConfig(int buildThreads);

// What Embree may use here: "the processor's widest", or e.g. "at most avx2
// (RAYCACHE_LANES)".
std::string embreeInstructionSet();

}  // namespace raycache
