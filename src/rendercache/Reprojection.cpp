#include "rendercache/Reprojection.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

namespace raycache {

namespace {

// Slots are handed to workers in chunks of this many.
constexpr std::size_t kChunk = 16384;

}  // namespace

std::vector<Vec3> objectOrigins(const Scene& scene) {
    std::vector<Vec3> origins;
    origins.reserve(scene.objects.size());
    for (const SceneObject& object : scene.objects) origins.push_back(object.origin);
    return origins;
}

ReprojectionCounts reproject(SamplePool& pool, const Scene& scene, const ScreenProjection& projection, int maxAge,
                             PointImage& image, std::vector<unsigned char>& shown, const Parallel& parallel,
                             std::vector<unsigned char>* scratch) {
    const std::size_t n = pool.capacity();
    const std::vector<Vec3> origins = objectOrigins(scene);
    const int chunks = static_cast<int>((n + kChunk - 1) / kChunk);
    std::vector<ReprojectionCounts> perChunk(static_cast<std::size_t>(chunks));
    // Offer every live sample; the depth test picks each pixel's winner.
    // Counts go to a local and are written once per chunk: neighbouring
    // chunks' counters share a cache line, and updating it per sample from
    // two threads cost more than the projection.
    parallel.forEachIndex(chunks, [&](int chunk, int) {
        ReprojectionCounts counts;
        const std::size_t end = std::min(n, (static_cast<std::size_t>(chunk) + 1) * kChunk);
        for (std::size_t slot = static_cast<std::size_t>(chunk) * kChunk; slot < end; ++slot) {
            if (pool.objectId[slot] == SamplePool::kEmpty) continue;
            if (pool.age[slot] >= maxAge) {
                pool.objectId[slot] = SamplePool::kEmpty;
                ++counts.evicted;
                continue;
            }
            ++pool.age[slot];
            int x, y;
            float depth;
            if (projectSample(pool, slot, origins, projection, x, y, depth) && image.covers(x, y))
                image.offer(x, y, depth, static_cast<std::uint32_t>(slot));
        }
        perChunk[static_cast<std::size_t>(chunk)] = counts;
    });
    // Mark the winners, and the pixels nobody won.
    std::vector<unsigned char>& won = shown;
    won.assign(n, 0);
    const int rows = image.height() + 2 * image.margin();
    const int stride = image.width() + 2 * image.margin();
    std::vector<unsigned char> ownScratch;
    std::vector<unsigned char>& emptyAfterFirst = scratch ? *scratch : ownScratch;
    emptyAfterFirst.resize(static_cast<std::size_t>(rows) * static_cast<std::size_t>(stride));  // all written below
    const auto emptyIndex = [&](int x, int y) {
        return static_cast<std::size_t>(y + image.margin()) * static_cast<std::size_t>(stride) +
               static_cast<std::size_t>(x + image.margin());
    };
    parallel.forEachIndex(rows, [&](int row, int) {
        const int y = row - image.margin();
        for (int x = -image.margin(); x < image.width() + image.margin(); ++x) {
            const bool has = image.hasSample(x, y);
            if (has) won[image.slotAt(x, y)] = 1;  // one pixel per slot: no race
            emptyAfterFirst[emptyIndex(x, y)] = has ? 0 : 1;
        }
    });
    // Second chance: losers offer themselves to the nearest neighbouring
    // pixel that the first round left empty (first-round winners stay).
    parallel.forEachIndex(chunks, [&](int chunk, int) {
        const std::size_t end = std::min(n, (static_cast<std::size_t>(chunk) + 1) * kChunk);
        for (std::size_t slot = static_cast<std::size_t>(chunk) * kChunk; slot < end; ++slot) {
            if (pool.objectId[slot] == SamplePool::kEmpty || won[slot]) continue;
            float px, py, depth;
            if (!projectSample(pool, slot, origins, projection, px, py, depth)) continue;
            const int x = static_cast<int>(std::floor(px)), y = static_cast<int>(std::floor(py));
            if (!image.covers(x, y)) continue;
            // The 8 neighbours, nearest centre first (a fixed order among
            // equals): the empty pixel beside a collision may lie on either side.
            const float fx = px - static_cast<float>(x) - 0.5f, fy = py - static_cast<float>(y) - 0.5f;
            std::array<std::pair<float, int>, 8> around;
            int k = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    if (dx == 0 && dy == 0) continue;
                    const float ex = static_cast<float>(dx) - fx, ey = static_cast<float>(dy) - fy;
                    around[static_cast<std::size_t>(k)] = {ex * ex + ey * ey, (dy + 1) * 3 + (dx + 1)};
                    ++k;
                }
            std::sort(around.begin(), around.end());
            for (const auto& [distance, code] : around) {
                const int nx = x + code % 3 - 1, ny = y + code / 3 - 1;
                if (!image.covers(nx, ny) || !emptyAfterFirst[emptyIndex(nx, ny)]) continue;
                image.offer(nx, ny, depth, static_cast<std::uint32_t>(slot));
                break;
            }
        }
    });
    parallel.forEachIndex(rows, [&](int row, int) {
        const int y = row - image.margin();
        for (int x = -image.margin(); x < image.width() + image.margin(); ++x)
            if (emptyAfterFirst[emptyIndex(x, y)] && image.hasSample(x, y)) won[image.slotAt(x, y)] = 2;
    });
    parallel.forEachIndex(chunks, [&](int chunk, int) {
        ReprojectionCounts counts = perChunk[static_cast<std::size_t>(chunk)];
        const std::size_t end = std::min(n, (static_cast<std::size_t>(chunk) + 1) * kChunk);
        for (std::size_t slot = static_cast<std::size_t>(chunk) * kChunk; slot < end; ++slot) {
            if (pool.objectId[slot] == SamplePool::kEmpty) continue;
            if (won[slot]) {
                ++counts.placed;
                if (won[slot] == 2) ++counts.moved;
            } else {
                pool.objectId[slot] = SamplePool::kEmpty;
                ++counts.lost;
            }
        }
        perChunk[static_cast<std::size_t>(chunk)] = counts;
    });
    ReprojectionCounts total;
    for (const ReprojectionCounts& c : perChunk) {
        total.placed += c.placed;
        total.moved += c.moved;
        total.evicted += c.evicted;
        total.lost += c.lost;
    }
    return total;
}

}  // namespace raycache
