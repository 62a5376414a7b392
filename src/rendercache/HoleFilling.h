#pragma once
// Image generation of the Render Cache (SPEC §6; enhanced Render Cache,
// Walter et al. 2002): pixels without a sample take the weighted mean of
// the samples among their 3x3 neighbours (edge neighbours count twice,
// corners once); pixels the 3x3 filter cannot reach take the mean of the
// samples in their 7x7 box (the prefilter), applied only there, like the
// stencil-masked pass of the GPU version.
#include <cstdint>
#include <vector>

#include "core/Image.h"
#include "core/Parallel.h"
#include "rendercache/PixelState.h"

namespace raycache {

struct FillCounts {
    std::int64_t filled3x3 = 0;
    std::int64_t filled7x7 = 0;
    std::int64_t unfilled = 0;  // left for the caller: state Unfilled, pixel untouched
};

// `film` holds the samples' colours where showsSample(state); the holes
// (isHole) are filled from those pixels only, and their state set to
// Filled3x3, Filled7x7 or Unfilled.
// `scratch`, when given, is reused from frame to frame (no allocation).
FillCounts fillHoles(std::vector<PixelState>& state, Image& film, const Parallel& parallel,
                     std::vector<unsigned char>* scratch = nullptr);

}  // namespace raycache
