// pixelStateBits() and forEachPixelSet() against the
// states they stand for, pixel by pixel: rows of every width from 1 to 200
// (whole words of sixteen-state tests, a tail one state at a time, both
// and neither).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "rendercache/PixelStateBits.h"

using namespace raycache;

namespace {

bool bitOf(const std::vector<std::uint64_t>& bits, int x) {
    return (bits[static_cast<std::size_t>(x / 64)] >> (x % 64)) & 1u;
}

}  // namespace

TEST(PixelStateBits, EachBitSaysWhetherItsPixelsStateIsOneOfTheTwoAndNothingPastTheRowIsSet) {
    std::mt19937 random(38);
    std::uniform_int_distribution<int> anyState(0, static_cast<int>(PixelState::Unfilled));
    for (int width = 1; width <= 200; ++width) {
        std::vector<PixelState> states(static_cast<std::size_t>(width));
        for (PixelState& s : states) s = static_cast<PixelState>(anyState(random));
        std::vector<std::uint64_t> samples(pixelStateWords(width), ~std::uint64_t{0}),
            holes(pixelStateWords(width), ~std::uint64_t{0});  // every word must be written
        pixelStateBits(states.data(), width, PixelState::Reprojected, PixelState::Fresh, samples.data());
        pixelStateBits(states.data(), width, PixelState::Culled, PixelState::Hole, holes.data());
        for (int x = 0; x < static_cast<int>(samples.size()) * 64; ++x) {
            const bool inRow = x < width;
            ASSERT_EQ(bitOf(samples, x), inRow && showsSample(states[static_cast<std::size_t>(x)]))
                << "width " << width << ", pixel " << x;
            ASSERT_EQ(bitOf(holes, x), inRow && isHole(states[static_cast<std::size_t>(x)]))
                << "width " << width << ", pixel " << x;
        }
        std::vector<std::uint64_t> filled(pixelStateWords(width), ~std::uint64_t{0});
        pixelStateBits(states.data(), width, PixelState::Filled3x3, PixelState::Filled7x7, filled.data());
        std::vector<int> visited, wanted;
        forEachPixelSet(filled.data(), width, [&](int x) { visited.push_back(x); });
        for (int x = 0; x < width; ++x) {
            const PixelState s = states[static_cast<std::size_t>(x)];
            if (s == PixelState::Filled3x3 || s == PixelState::Filled7x7) wanted.push_back(x);
        }
        ASSERT_EQ(visited, wanted) << "width " << width;  // each once, from left to right
    }
}
