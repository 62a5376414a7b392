#include "rendercache/Reprojection.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "core/Elapsed.h"
#include "core/Errors.h"

namespace raycache {

namespace {

using Landed = ReprojectionScratch::Landed;

// A packed key: the depth's bits (positive floats, +infinity included,
// order as their bits do) above the source slot, so that the minimum is
// the nearest sample and equal depths go to the lower slot, the rule the
// untiled depth test had. The minimum does not depend on the order the
// offers come in, so neither does the outcome on the thread count.
std::uint64_t packedReprojectionKey(float depth, std::uint32_t slot) {
    return (static_cast<std::uint64_t>(PointImage::key(depth)) << 32) | slot;
}
// Empty after the first round: no key, or only second-chance offers
// (kSecondChanceMark: such offers go only to pixels no sample landed in,
// so among themselves they still order by (depth, slot), and the mark
// tells the other losers that the pixel was empty after the first round).
bool emptyBeforeSecondChance(std::uint64_t key) { return (key & kSecondChanceMark) != 0; }

// How far around a tile its samples are binned: the tile is resolved with
// a one-pixel ring (for the visitor's 3x3 neighbourhoods); a loser moves at
// most one pixel, so losers landing two pixels out reach the ring, and
// where they go depends on which of their neighbours, three pixels out,
// are empty.
constexpr int kTileApron = 3;

// The tiles (0-based) whose tile-plus-apron spans position `u` (0 at the
// margin's first pixel) on an axis of `tiles` tiles of `side` pixels.
void tilesReachingPosition(int u, int side, int tiles, int& first, int& last) {
    first = u < kTileApron ? 0 : (u - kTileApron) / side;
    last = std::min(tiles - 1, (u + kTileApron) / side);
}

}  // namespace

std::vector<Vec3> objectOrigins(const Scene& scene) {
    std::vector<Vec3> origins;
    origins.reserve(scene.objects.size());
    for (const SceneObject& object : scene.objects) origins.push_back(object.origin);
    return origins;
}

ReprojectionCounts reproject(const SamplePool& from, SamplePool& to, const Scene& scene,
                             const ScreenProjection& projection, int maxAge, PointImage& image,
                             const Parallel& parallel, ReprojectionScratch& scratch, const ScreenProjection* next,
                             std::vector<std::int32_t>* nextPixel, int tileSide, const ResolvedTileVisitor& onTile) {
    if (to.capacity() != from.capacity() || to.pixelSlots != image.pixelCount() ||
        from.pixelSlots != image.pixelCount() || (next && !nextPixel))
        throw RuntimeError("reproject: the pools do not fit the image");
    if (tileSide < 1) throw RuntimeError("reproject: the tile side must be at least 1");
    const std::vector<Vec3> origins = objectOrigins(scene);
    const int rows = image.rows();
    const int stride = image.stride();
    const int margin = image.margin();
    const int tilesX = (stride + tileSide - 1) / tileSide, tilesY = (rows + tileSide - 1) / tileSide;
    const int tiles = tilesX * tilesY;
    scratch.tilesX = tilesX;
    scratch.tilesY = tilesY;
    // Chunks of the source pool as tall as a tile: the pool is in pixel
    // order (the last frame's), so a chunk's samples land in about three
    // rows of tiles and its lists stay few and long.
    const std::size_t chunkSlots = static_cast<std::size_t>(tileSide) * static_cast<std::size_t>(stride);
    const std::size_t used = from.used();
    const int chunks = static_cast<int>((used + chunkSlots - 1) / chunkSlots);
    const std::size_t lists = static_cast<std::size_t>(chunks) * static_cast<std::size_t>(tiles);
    if (scratch.bins.size() < lists) scratch.bins.resize(lists);
    for (std::size_t i = 0; i < lists; ++i) scratch.bins[i].clear();
    if (next) {
        scratch.nextPixel.resize(from.capacity());  // written for every sample that lands
        nextPixel->resize(to.pixelSlots);           // every pixel slot written below
    }
    std::int32_t* nextOfSource = scratch.nextPixel.data();

    // Binning: project every live sample once and list it in the tile it
    // lands in (and the tiles whose apron it lands in). Counts go to a
    // local written once per chunk: counters side by side share a cache
    // line, and updating it per sample from two threads costs more than
    // the projection.
    const auto binStart = std::chrono::steady_clock::now();
    struct ChunkCounts {
        std::int64_t live = 0, evicted = 0;
    };
    std::vector<ChunkCounts> perChunk(static_cast<std::size_t>(chunks));
    const SamplePoint* fromPoint = from.point.data();
    const SampleLook* fromLook = from.look.data();
    parallel.forEachIndex(chunks, [&](int chunk, int) {
        std::vector<Landed>* chunkBins = scratch.bins.data() + static_cast<std::size_t>(chunk) * tiles;
        ChunkCounts counts;
        const std::size_t begin = static_cast<std::size_t>(chunk) * chunkSlots;
        const std::size_t end = std::min(used, begin + chunkSlots);
        for (std::size_t slot = begin; slot < end; ++slot) {
            if (fromPoint[slot].objectId == SamplePool::kEmpty) continue;
            ++counts.live;
            if (fromLook[slot].age >= maxAge) {
                ++counts.evicted;
                continue;
            }
            float px, py, depth;
            if (!projectSample(from, slot, origins, projection, px, py, depth)) continue;
            const int x = ScreenProjection::pixelOf(px), y = ScreenProjection::pixelOf(py);
            if (!image.covers(x, y)) continue;
            if (next) nextOfSource[slot] = imagePixelThrough(from, slot, origins, *next, image.width(), image.height());
            const Landed landed{packedReprojectionKey(depth, static_cast<std::uint32_t>(slot)), px, py};
            int tx0, tx1, ty0, ty1;
            tilesReachingPosition(x + margin, tileSide, tilesX, tx0, tx1);
            tilesReachingPosition(y + margin, tileSide, tilesY, ty0, ty1);
            for (int ty = ty0; ty <= ty1; ++ty)
                for (int tx = tx0; tx <= tx1; ++tx) chunkBins[ty * tilesX + tx].push_back(landed);
        }
        perChunk[static_cast<std::size_t>(chunk)] = counts;
    });

    const double binMs = millisecondsSince(binStart);

    // Resolving: each tile on one thread, in its own buffer.
    const auto resolveStart = std::chrono::steady_clock::now();
    scratch.tileKeys.resize(static_cast<std::size_t>(parallel.threadCount()));
    std::vector<std::int64_t> placedPerTile(static_cast<std::size_t>(tiles), 0);
    std::vector<std::int64_t> movedPerTile(static_cast<std::size_t>(tiles), 0);
    parallel.forEachIndex(tiles, [&](int tile, int worker) {
        // The tile, in positions from 0 at the margin's first pixel.
        const int u0 = (tile % tilesX) * tileSide, v0 = (tile / tilesX) * tileSide;
        const int u1 = std::min(stride, u0 + tileSide), v1 = std::min(rows, v0 + tileSide);
        const int bufferWidth = u1 - u0 + 2 * kTileApron;
        std::vector<std::uint64_t>& keys = scratch.tileKeys[static_cast<std::size_t>(worker)];
        keys.assign(static_cast<std::size_t>(bufferWidth) * static_cast<std::size_t>(v1 - v0 + 2 * kTileApron),
                    kNoReprojectedSample);
        const auto at = [&](int u, int v) {
            return static_cast<std::size_t>(v - v0 + kTileApron) * static_cast<std::size_t>(bufferWidth) +
                   static_cast<std::size_t>(u - u0 + kTileApron);
        };
        const auto forEachLanded = [&](const auto& body) {
            for (int chunk = 0; chunk < chunks; ++chunk)
                for (const Landed& l : scratch.bins[static_cast<std::size_t>(chunk) * tiles + tile]) body(l);
        };

        // First round: the nearest sample wins each pixel of the tile and
        // its apron (every sample landing there is in this tile's lists).
        forEachLanded([&](const Landed& l) {
            const int u = ScreenProjection::pixelOf(l.x) + margin, v = ScreenProjection::pixelOf(l.y) + margin;
            std::uint64_t& key = keys[at(u, v)];
            key = std::min(key, l.key);
        });

        // Second chance: a loser offers itself to the nearest neighbouring
        // pixel that the first round left empty (first-round winners stay).
        // Only offers to this tile's own pixels and its ring are taken
        // here; the tile that holds the target takes them too.
        forEachLanded([&](const Landed& l) {
            const int x = ScreenProjection::pixelOf(l.x), y = ScreenProjection::pixelOf(l.y);
            const int u = x + margin, v = y + margin;
            if (u < u0 - 2 || u > u1 + 1 || v < v0 - 2 || v > v1 + 1) return;  // too far to reach the ring
            if (keys[at(u, v)] == l.key) return;  // the winner of its pixel
            // The nearest empty neighbour by distance to its centre; among
            // equals the first in row order (a fixed order).
            const float fx = l.x - static_cast<float>(x) - 0.5f, fy = l.y - static_cast<float>(y) - 0.5f;
            float nearest = std::numeric_limits<float>::infinity();
            int bestU = 0, bestV = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    if (dx == 0 && dy == 0) continue;
                    if (!image.covers(x + dx, y + dy) || !emptyBeforeSecondChance(keys[at(u + dx, v + dy)])) continue;
                    const float ex = static_cast<float>(dx) - fx, ey = static_cast<float>(dy) - fy;
                    const float distance = ex * ex + ey * ey;
                    if (distance < nearest) {
                        nearest = distance;
                        bestU = u + dx;
                        bestV = v + dy;
                    }
                }
            if (nearest == std::numeric_limits<float>::infinity()) return;
            if (bestU < u0 - 1 || bestU > u1 || bestV < v0 - 1 || bestV > v1) return;
            std::uint64_t& key = keys[at(bestU, bestV)];
            key = std::min(key, l.key | kSecondChanceMark);
        });

        // Each pixel's winner to its own slot of `to` (two 16-byte records
        // and, for a sample that depends on the eye, its reshading inputs),
        // its depth to the image. The arrays' addresses in locals: the
        // compiler cannot tell that the stores do not change the vectors.
        const ReshadeInputs* fromReshade = from.reshade.data();
        SamplePoint* toPoint = to.point.data();
        SampleLook* toLook = to.look.data();
        ReshadeInputs* toReshade = to.reshade.data();
        std::int32_t* nextOfPixel = next ? nextPixel->data() : nullptr;
        std::int64_t placed = 0, moved = 0;
        for (int v = v0; v < v1; ++v)
            for (int u = u0; u < u1; ++u) {
                const std::size_t pixel = static_cast<std::size_t>(v) * static_cast<std::size_t>(stride) +
                                          static_cast<std::size_t>(u);
                const std::uint64_t key = keys[at(u, v)];
                if (key == kNoReprojectedSample) {
                    toPoint[pixel].objectId = SamplePool::kEmpty;
                    if (nextOfPixel) nextOfPixel[pixel] = -1;
                    continue;
                }
                const auto source = static_cast<std::size_t>(key & 0xffffffffu);
                moved += (key & kSecondChanceMark) ? 1 : 0;
                image.setKey(u - margin, v - margin, static_cast<std::uint32_t>((key & ~kSecondChanceMark) >> 32));
                if (nextOfPixel) nextOfPixel[pixel] = nextOfSource[source];
                toPoint[pixel] = fromPoint[source];
                SampleLook look = fromLook[source];
                look.age = static_cast<std::uint16_t>(look.age + 1);
                toLook[pixel] = look;
                // What reshading needs, only where it means something.
                if (look.viewDependent) toReshade[pixel] = fromReshade[source];
                ++placed;
            }
        placedPerTile[static_cast<std::size_t>(tile)] = placed;
        movedPerTile[static_cast<std::size_t>(tile)] = moved;
        if (onTile) {
            const TileRange pixels{u0 - margin, v0 - margin, u1 - margin, v1 - margin};
            onTile(ResolvedTile(keys.data(), static_cast<std::size_t>(bufferWidth), pixels.x0 - kTileApron,
                                pixels.y0 - kTileApron, pixels));
        }
    });
    to.overflowUsed = 0;

    ReprojectionCounts total;
    total.binMs = binMs;
    total.resolveMs = millisecondsSince(resolveStart);
    for (std::int64_t p : placedPerTile) total.placed += p;
    for (std::int64_t m : movedPerTile) total.moved += m;
    std::int64_t live = 0;
    for (const ChunkCounts& c : perChunk) {
        live += c.live;
        total.evicted += c.evicted;
    }
    total.lost = live - total.evicted - total.placed;
    return total;
}

}  // namespace raycache
