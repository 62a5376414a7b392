#pragma once
// A row of pixel states as bits, 64 pixels a word, for the hole fills: one
// test of sixteen states at a time instead of a load and a branch per pixel
// (the 3x3 fill tested each hole's nine neighbours and copied each sample's
// colour one pixel at a time, a third of its instructions).
#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

#include "rendercache/PixelState.h"

namespace raycache {

// Words a row of `width` pixels takes, plus one of slack so that
// threeBitsAround() may read eight bytes from any pixel of the row.
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

// The bits of pixels x - 1, x and x + 1 as bits 0, 1 and 2 (0 where x - 1
// is -1; `bits` from pixelStateBits(), so 0 past the row's end).
inline unsigned threeBitsAround(const std::uint64_t* bits, int x) {
    const auto bytes = reinterpret_cast<const unsigned char*>(bits);
    const int from = x > 0 ? x - 1 : 0;
    std::uint64_t word;
    std::memcpy(&word, bytes + from / 8, sizeof word);  // little-endian: bit i of the row is bit i % 8 of byte i / 8
    const auto three = static_cast<unsigned>(word >> (from % 8)) & 7u;
    return x > 0 ? three : (three << 1) & 7u;
}

}  // namespace raycache
