#include "rendercache/RequestMap.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <cmath>
#include <emmintrin.h>

namespace raycache {

namespace {

// Inside a tile, priorities in kLevels steps; holes (1) on the top one.
constexpr int kLevels = 33;
unsigned char levelOf(float priority) {
    return static_cast<unsigned char>(std::clamp(priority, 0.0f, 1.0f) * static_cast<float>(kLevels - 1));
}
// levelOf() of eight priorities at once: the same operations lane by lane
// (the clamp's two selects, the product, the conversion's truncation; the
// levels fit the packs' saturation, and a NaN gives 0 both ways).
constexpr int kLevelLanes = 8;
void levelsOf(const float* priorities, unsigned char* levels) {
    const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), top = _mm_set1_ps(static_cast<float>(kLevels - 1));
    const auto fourLevels = [&](const float* p) {
        __m128 v = _mm_loadu_ps(p);
        v = _mm_max_ps(zero, v);  // p < 0 ? 0 : p (a NaN stays)
        v = _mm_min_ps(one, v);   // 1 < p ? 1 : p
        return _mm_cvttps_epi32(_mm_mul_ps(v, top));
    };
    const __m128i words = _mm_packs_epi32(fourLevels(priorities), fourLevels(priorities + 4));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(levels), _mm_packus_epi16(words, words));
}

}  // namespace

std::uint64_t mixBits(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

std::int64_t pixelsInTilesWithRequests(const RequestMap& map, int width, int height) {
    std::int64_t pixels = 0;
    for (std::size_t t = 0; t < map.tileRequests.size(); ++t) {
        if (map.tileRequests[t] == 0) continue;
        const TileRect r = tileRectOf(map, t, width, height);
        pixels += static_cast<std::int64_t>(r.x1 - r.x0) * static_cast<std::int64_t>(r.y1 - r.y0);
    }
    return pixels;
}

void buildRequestMap(std::span<const float> priority, int width, int height, int tileSize, float alpha, int budget,
                     std::uint64_t seed, std::uint64_t frame, RequestMap& out, const Parallel& parallel) {
    out.tileSize = tileSize;
    out.tilesX = (width + tileSize - 1) / tileSize;
    out.tilesY = (height + tileSize - 1) / tileSize;
    const auto tiles = static_cast<std::size_t>(out.tilesX) * static_cast<std::size_t>(out.tilesY);
    out.tilePriority.assign(tiles, 0.0f);
    out.tileRequests.assign(tiles, 0);
    out.pixels.clear();
    const auto pixelIndex = [width](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    };

    // The priority map, a row of tiles per task (a task per 8x8 tile cost
    // about as much as summing it).
    parallel.forEachIndex(out.tilesY, [&](int tileRow, int) {
        const float* const values = priority.data();
        float* const sums = out.tilePriority.data();
        for (auto t = static_cast<std::size_t>(tileRow) * static_cast<std::size_t>(out.tilesX);
             t < static_cast<std::size_t>(tileRow + 1) * static_cast<std::size_t>(out.tilesX); ++t) {
            const auto [x0, y0, x1, y1] = tileRectOf(out, t, width, height);
            double q = 0.0;  // per tile in double, then one float: the same sum on any thread
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) q += values[pixelIndex(x, y)];
            sums[t] = static_cast<float>(q);
        }
    });
    if (budget <= 0) return;
    double totalPriority = 0.0;
    for (float q : out.tilePriority) totalPriority += q;
    const double pixels = static_cast<double>(width) * static_cast<double>(height);
    const double priorityWeight = totalPriority > 0.0 ? alpha : 0.0;

    // The request map: systematic sampling of the tiles' shares.
    const double start = static_cast<double>(mixBits(seed ^ mixBits(frame)) >> 11) * 0x1.0p-53;
    double cumulative = 0.0;
    double previous = std::floor(start);
    for (std::size_t t = 0; t < tiles; ++t) {
        const auto [x0, y0, x1, y1] = tileRectOf(out, t, width, height);
        const double area = static_cast<double>(x1 - x0) * static_cast<double>(y1 - y0);
        double share = (1.0 - priorityWeight) * area / pixels;
        if (priorityWeight > 0.0) share += priorityWeight * out.tilePriority[t] / totalPriority;
        cumulative += share;
        const double reached = std::floor(static_cast<double>(budget) * cumulative + start);
        out.tileRequests[t] = static_cast<int>(std::min(area, reached - previous));
        previous = reached;
    }

    // Inside each tile: the highest priorities, random among equals.
    std::vector<std::size_t> firstRequest(tiles + 1, 0);
    for (std::size_t t = 0; t < tiles; ++t)
        firstRequest[t + 1] = firstRequest[t] + static_cast<std::size_t>(out.tileRequests[t]);
    out.pixels.resize(firstRequest[tiles]);
    const std::uint64_t frameSeed = mixBits(seed ^ mixBits(frame));
    std::vector<std::vector<unsigned char>> levelsPerWorker(static_cast<std::size_t>(parallel.threadCount()));
    // A row of tiles per task, as the priority map.
    const auto requestsOfTile = [&](std::size_t t, std::vector<unsigned char>& levels) {
        const int wanted = out.tileRequests[t];
        if (wanted == 0) return;
        const auto [x0, y0, x1, y1] = tileRectOf(out, t, width, height);
        const int tileWidth = x1 - x0;
        const int n = tileWidth * (y1 - y0);
        levels.resize(static_cast<std::size_t>(n));
        std::array<int, kLevels> perLevel{};
        for (int y = y0; y < y1; ++y) {
            // A row's levels first, four at a time, then their histogram (one
            // pixel at a time with both in one loop: 21 instructions a pixel).
            const float* const values = priority.data() + pixelIndex(x0, y);
            unsigned char* const rowLevels = levels.data() + static_cast<std::size_t>((y - y0) * tileWidth);
            int i = 0;
            for (; i + kLevelLanes <= tileWidth; i += kLevelLanes) levelsOf(values + i, rowLevels + i);
            for (; i < tileWidth; ++i) rowLevels[i] = levelOf(values[i]);
            for (i = 0; i < tileWidth; ++i) ++perLevel[rowLevels[i]];
        }
        // The lowest level taken, and how many of it.
        int cut = kLevels - 1, above = 0;
        while (cut > 0 && above + perLevel[static_cast<std::size_t>(cut)] < wanted)
            above += perLevel[static_cast<std::size_t>(cut--)];
        int fromCut = wanted - above;
        // Among equals, a random order: the tile's pixels visited with a
        // random start and a random stride prime to their count, one hash per tile.
        const std::uint64_t h = mixBits(frameSeed ^ t);
        int at = static_cast<int>(h % static_cast<std::uint64_t>(n));
        int stride = n > 1 ? 1 + static_cast<int>((h >> 32) % static_cast<std::uint64_t>(n - 1)) : 1;
        while (std::gcd(stride, n) != 1) ++stride;
        stride %= n;
        std::size_t next = firstRequest[t];
        for (int visited = 0; visited < n && next < firstRequest[t + 1]; ++visited) {
            const int level = levels[static_cast<std::size_t>(at)];
            if (level > cut || (level == cut && fromCut > 0)) {
                if (level == cut) --fromCut;
                out.pixels[next++] = {x0 + at % tileWidth, y0 + at / tileWidth};
            }
            at += stride;
            if (at >= n) at -= n;
        }
    };
    parallel.forEachIndex(out.tilesY, [&](int tileRow, int worker) {
        std::vector<unsigned char>& levels = levelsPerWorker[static_cast<std::size_t>(worker)];
        for (auto t = static_cast<std::size_t>(tileRow) * static_cast<std::size_t>(out.tilesX);
             t < static_cast<std::size_t>(tileRow + 1) * static_cast<std::size_t>(out.tilesX); ++t)
            requestsOfTile(t, levels);
    });
}

}  // namespace raycache
