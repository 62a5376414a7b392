#pragma once
// The primitives of every cell of a grid, listed by sorting the (cell,
// primitive) pairs by cell in one counting pass: an LSD radix sort whose
// single digit is the whole cell index. Per block of primitives (one per
// thread) the pairs of each cell are counted, the counts scanned cell by
// cell and block by block into write positions, and every pair written to
// its position. The pairs themselves are never stored: a primitive's cells
// are generated twice, once to count and once to write.
//
// Stable: a cell lists its primitives in primitive order, whatever the
// thread count (the lists are those a stable sort of the pairs gives).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "core/Parallel.h"

namespace raycache {

class CellLists {
public:
    // Lists `primitives` primitives over `cells` cells. cellsOf(p, visit)
    // calls visit(cell) for every cell of primitive p, the same cells in
    // the same order each time it is called, each cell below `cells`.
    // `pairs`: how many cells all primitives have together.
    template <typename CellsOf>
    void build(std::uint32_t primitives, std::uint64_t cells, std::uint64_t pairs, const Parallel& parallel,
               CellsOf&& cellsOf) {
        if (pairs > std::numeric_limits<std::uint32_t>::max() || cells >= std::numeric_limits<std::uint32_t>::max())
            throw RuntimeError("a grid would need " + std::to_string(pairs) + " (cell, primitive) pairs in " +
                               std::to_string(cells) + " cells");
        // One block per thread, as long as the blocks' counters stay small
        // beside the caches; beyond that one block (a serial count).
        int blocks = std::max(1, parallel.threadCount());
        if (cells * static_cast<std::uint64_t>(blocks) > kMaxCounters || primitives < kMinBlockPrimitives) blocks = 1;
        const std::uint32_t perBlock =
            (primitives + static_cast<std::uint32_t>(blocks) - 1) / static_cast<std::uint32_t>(blocks);
        const std::size_t stride = static_cast<std::size_t>(cells);
        counts_.assign(stride * static_cast<std::size_t>(blocks), 0);
        const auto blockRange = [&](int b) {
            const std::uint32_t begin = std::min(primitives, static_cast<std::uint32_t>(b) * perBlock);
            return std::pair{begin, std::min(primitives, begin + perBlock)};
        };
        parallel.forEachIndex(blocks, [&](int b, int) {
            std::uint32_t* count = counts_.data() + stride * static_cast<std::size_t>(b);
            const auto [begin, end] = blockRange(b);
            for (std::uint32_t p = begin; p < end; ++p) cellsOf(p, [&](std::size_t cell) { ++count[cell]; });
        });
        // Cell-major, block-minor: block b's pairs of cell c follow those of
        // every earlier cell and of cell c in earlier blocks.
        cellStart_.resize(stride + 1);
        std::uint32_t running = 0;
        for (std::size_t c = 0; c < stride; ++c) {
            cellStart_[c] = running;
            for (std::size_t b = 0; b < static_cast<std::size_t>(blocks); ++b) {
                std::uint32_t& count = counts_[b * stride + c];
                const std::uint32_t n = count;
                count = running;
                running += n;
            }
        }
        cellStart_[stride] = running;
        if (running != pairs) throw RuntimeError("CellLists: the cells counted differ from the pairs announced");
        cellPrimitives_.resize(running);
        parallel.forEachIndex(blocks, [&](int b, int) {
            std::uint32_t* next = counts_.data() + stride * static_cast<std::size_t>(b);
            const auto [begin, end] = blockRange(b);
            for (std::uint32_t p = begin; p < end; ++p)
                cellsOf(p, [&](std::size_t cell) { cellPrimitives_[next[cell]++] = p; });
        });
    }

    // cells + 1 offsets into primitives(): cell c lists primitives()[start(c), start(c + 1)).
    const std::vector<std::uint32_t>& cellStart() const { return cellStart_; }
    const std::vector<std::uint32_t>& primitives() const { return cellPrimitives_; }

private:
    // 16 MiB of counters at most when counting in parallel.
    static constexpr std::uint64_t kMaxCounters = std::uint64_t{1} << 22;
    // Below this many primitives a second block is not worth its counters.
    static constexpr std::uint32_t kMinBlockPrimitives = 4096;
    std::vector<std::uint32_t> counts_;  // per block and cell; reused from frame to frame
    std::vector<std::uint32_t> cellStart_;
    std::vector<std::uint32_t> cellPrimitives_;
};

}  // namespace raycache
