#include "rendercache/HoleFilling.h"

namespace raycache {

namespace {

constexpr int kPrefilterRadius = 3;  // 7x7

}  // namespace

FillCounts fillHoles(std::vector<PixelState>& state, Image& film, const Parallel& parallel,
                     std::vector<unsigned char>* scratch) {
    const int width = film.width(), height = film.height();
    const auto at = [width](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    };
    // Both passes read `state` and the colours of pixels showing a sample,
    // and write only the colours of holes and `outcome`: rows run in any
    // order, without a data race. The states change at the end.
    enum Outcome : unsigned char { kNone, k3x3, k7x7, kUnfilled };
    std::vector<unsigned char> ownScratch;
    std::vector<unsigned char>& outcome = scratch ? *scratch : ownScratch;
    outcome.assign(state.size(), kNone);
    std::vector<FillCounts> perRow(static_cast<std::size_t>(height));
    // Counts per row go to a local, written once (no false sharing).
    parallel.forEachIndex(height, [&](int y, int) {
        FillCounts row;
        for (int x = 0; x < width; ++x) {
            if (!isHole(state[at(x, y)])) continue;
            Rgb sum;
            float weight = 0.0f;
            for (int dy = -1; dy <= 1; ++dy) {
                const int ny = y + dy;
                if (ny < 0 || ny >= height) continue;
                for (int dx = -1; dx <= 1; ++dx) {
                    const int nx = x + dx;
                    if (nx < 0 || nx >= width || !showsSample(state[at(nx, ny)])) continue;
                    const float w = (dx == 0 || dy == 0) ? 2.0f : 1.0f;
                    sum += film.at(nx, ny) * w;
                    weight += w;
                }
            }
            if (weight > 0.0f) {
                film.at(x, y) = sum * (1.0f / weight);
                outcome[at(x, y)] = k3x3;
                ++row.filled3x3;
            }
        }
        perRow[static_cast<std::size_t>(y)] = row;
    });
    parallel.forEachIndex(height, [&](int y, int) {
        FillCounts row = perRow[static_cast<std::size_t>(y)];
        for (int x = 0; x < width; ++x) {
            if (!isHole(state[at(x, y)]) || outcome[at(x, y)] == k3x3) continue;
            Rgb sum;
            int count = 0;
            for (int ny = std::max(0, y - kPrefilterRadius); ny <= std::min(height - 1, y + kPrefilterRadius); ++ny)
                for (int nx = std::max(0, x - kPrefilterRadius); nx <= std::min(width - 1, x + kPrefilterRadius); ++nx)
                    if (showsSample(state[at(nx, ny)])) {
                        sum += film.at(nx, ny);
                        ++count;
                    }
            if (count > 0) {
                film.at(x, y) = sum * (1.0f / static_cast<float>(count));
                outcome[at(x, y)] = k7x7;
                ++row.filled7x7;
            } else {
                outcome[at(x, y)] = kUnfilled;
                ++row.unfilled;
            }
        }
        perRow[static_cast<std::size_t>(y)] = row;
    });
    parallel.forEachIndex(height, [&](int y, int) {
        for (std::size_t i = at(0, y); i < at(0, y) + static_cast<std::size_t>(width); ++i) {
            if (outcome[i] == k3x3) state[i] = PixelState::Filled3x3;
            else if (outcome[i] == k7x7) state[i] = PixelState::Filled7x7;
            else if (outcome[i] == kUnfilled) state[i] = PixelState::Unfilled;
        }
    });
    FillCounts total;
    for (const FillCounts& c : perRow) {
        total.filled3x3 += c.filled3x3;
        total.filled7x7 += c.filled7x7;
        total.unfilled += c.unfilled;
    }
    return total;
}

}  // namespace raycache
