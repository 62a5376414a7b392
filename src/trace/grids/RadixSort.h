#pragma once
// Parallel least-significant-digit radix sort of (key, value) pairs, the
// sort of the grids' (cell, primitive) lists. Stable: pairs with equal keys
// keep their input order, so the result does not depend on the thread count.
#include <cstdint>
#include <vector>

#include "core/Parallel.h"

namespace raycache {

// Sorts keys (all below 2^keyBits) and carries values along. The scratch
// vectors are reused between calls to avoid allocating every frame.
void radixSortPairs(std::vector<std::uint32_t>& keys, std::vector<std::uint32_t>& values, int keyBits,
                    const Parallel& parallel, std::vector<std::uint32_t>& keyScratch,
                    std::vector<std::uint32_t>& valueScratch);

}  // namespace raycache
