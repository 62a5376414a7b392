#pragma once
// A row of pixel states as bits, 64 pixels a word, for the passes that visit
// a few kinds of pixel (holes, filled holes, samples to reshade): one test
// of sixteen states at a time, then only the pixels whose bit is set,
// instead of a load and a branch per pixel.
#include <bit>
#include <cstdint>
#include <vector>

#include "rendercache/PixelState.h"

namespace raycache {

// Words a row of `width` pixels takes, plus one of slack (a reader may
// take a register of bits from any pixel of the row).
inline std::size_t pixelStateWords(int width) {
    return static_cast<std::size_t>(width + 63) / 64 + 1;
}

// Pixel x of states[0, width) as bit x % 64 of word x / 64 of `bits`
// (pixelStateWords(width) words, the bits past the row cleared): set where
// the state is `first` or `last` (two consecutive states, as showsSample()
// and isHole() ask).
// The pairs asked for: showsSample(), isHole(), and a hole either filter filled.
static_assert(static_cast<int>(PixelState::Fresh) == static_cast<int>(PixelState::Reprojected) + 1 &&
              static_cast<int>(PixelState::Hole) == static_cast<int>(PixelState::Culled) + 1 &&
              static_cast<int>(PixelState::Filled7x7) == static_cast<int>(PixelState::Filled3x3) + 1);
void pixelStateBits(const PixelState* states, int width, PixelState first, PixelState last, std::uint64_t* bits);

// Calls visit(x) for every pixel x whose bit is set in `bits`
// (pixelStateWords(width) words from pixelStateBits()), from left to right.
template <class Visit>
void forEachPixelSet(const std::uint64_t* bits, int width, const Visit& visit) {
    for (std::size_t w = 0; w + 1 < pixelStateWords(width); ++w)
        for (std::uint64_t b = bits[w]; b; b &= b - 1) visit(static_cast<int>(w * 64) + std::countr_zero(b));
}

}  // namespace raycache
