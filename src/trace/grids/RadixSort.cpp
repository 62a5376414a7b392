#include "trace/grids/RadixSort.h"

#include <algorithm>
#include <array>

namespace raycache {

namespace {

// Digits of at most 11 bits: a 20-bit key (a grid of a million cells) takes
// two passes of 10 bits rather than three of 8, and a block's 2048 running
// offsets and write positions still fit the caches.
constexpr int kMaxDigitBits = 11;
constexpr std::size_t kMaxDigits = std::size_t{1} << kMaxDigitBits;
// Below this many pairs a block is not worth a task of its own.
constexpr std::size_t kMinBlock = 1 << 15;

}  // namespace

void radixSortPairs(std::vector<std::uint32_t>& keys, std::vector<std::uint32_t>& values, int keyBits,
                    const Parallel& parallel, std::vector<std::uint32_t>& keyScratch,
                    std::vector<std::uint32_t>& valueScratch) {
    const std::size_t n = keys.size();
    if (n < 2 || keyBits <= 0) return;
    keyScratch.resize(n);
    valueScratch.resize(n);
    const std::size_t blocks =
        std::clamp<std::size_t>(n / kMinBlock, 1, static_cast<std::size_t>(4 * parallel.threadCount()));
    const std::size_t blockSize = (n + blocks - 1) / blocks;
    const int passes = (keyBits + kMaxDigitBits - 1) / kMaxDigitBits;
    const int digitBits = (keyBits + passes - 1) / passes;
    const std::size_t digits = std::size_t{1} << digitBits;
    std::vector<std::array<std::size_t, kMaxDigits>> offsets(blocks);
    for (int shift = 0; shift < keyBits; shift += digitBits) {
        parallel.forEachIndex(static_cast<int>(blocks), [&](int b, int) {
            auto& histogram = offsets[static_cast<std::size_t>(b)];
            std::fill(histogram.begin(), histogram.begin() + static_cast<std::ptrdiff_t>(digits), 0);
            const std::size_t begin = static_cast<std::size_t>(b) * blockSize, end = std::min(n, begin + blockSize);
            for (std::size_t i = begin; i < end; ++i) ++histogram[(keys[i] >> shift) & (digits - 1)];
        });
        // Digit-major, block-minor exclusive scan: block b's pairs of digit d
        // follow every pair of a smaller digit and those of digit d in earlier blocks.
        std::size_t running = 0;
        for (std::size_t d = 0; d < digits; ++d)
            for (std::size_t b = 0; b < blocks; ++b) {
                const std::size_t count = offsets[b][d];
                offsets[b][d] = running;
                running += count;
            }
        parallel.forEachIndex(static_cast<int>(blocks), [&](int b, int) {
            auto& next = offsets[static_cast<std::size_t>(b)];
            const std::size_t begin = static_cast<std::size_t>(b) * blockSize, end = std::min(n, begin + blockSize);
            for (std::size_t i = begin; i < end; ++i) {
                const std::size_t at = next[(keys[i] >> shift) & (digits - 1)]++;
                keyScratch[at] = keys[i];
                valueScratch[at] = values[i];
            }
        });
        keys.swap(keyScratch);
        values.swap(valueScratch);
    }
}

}  // namespace raycache
