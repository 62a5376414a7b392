#pragma once
// Where a frame's rays go (Walter et al. 1999; Zhu, Wang and Luebke 2005): the
// image is cut into square tiles; a tile's priority Q is the sum of its
// pixels' priorities (holes count 1, samples their age's share of the
// maximum); the request map gives each tile the share
//     w = (1 - alpha) * uniform + alpha * Q / sum(Q)
// of the frame's ray budget (uniform: the tile's share of the pixels), and
// inside a tile the rays go to the pixels of highest priority (in 33 steps), ties broken
// at random. Counts are rounded by systematic sampling with a random start,
// so a budget below one ray per tile still reaches every tile over frames.
// Everything random is a hash of (seed, frame, tile): the same inputs give
// the same requests on any number of threads.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/Parallel.h"
#include "render/CameraRays.h"

namespace raycache {

struct RequestMap {
    int tileSize = 8;
    int tilesX = 0, tilesY = 0;
    std::vector<float> tilePriority;  // Q per tile, row-major
    std::vector<int> tileRequests;    // rays given to each tile
    std::vector<PixelCoord> pixels;   // the requested pixels, tile by tile
};

// Fills `out` for an image of width x height whose pixel priorities (row
// major, each in [0, 1]) are `priority`. budget >= 0 rays; a tile gets at
// most as many as it has pixels.
void buildRequestMap(std::span<const float> priority, int width, int height, int tileSize, float alpha, int budget,
                     std::uint64_t seed, std::uint64_t frame, RequestMap& out, const Parallel& parallel);

// Tile `t` of `map` (row-major) over a width x height image: pixels
// [x0, x1) x [y0, y1), clipped at the image's right and bottom edges.
struct TileRect {
    int x0, y0, x1, y1;
};
inline TileRect tileRectOf(const RequestMap& map, std::size_t t, int width, int height) {
    const int x0 = static_cast<int>(t % static_cast<std::size_t>(map.tilesX)) * map.tileSize;
    const int y0 = static_cast<int>(t / static_cast<std::size_t>(map.tilesX)) * map.tileSize;
    return {x0, y0, std::min(width, x0 + map.tileSize), std::min(height, y0 + map.tileSize)};
}

// The pixels of `map`'s tiles that got at least one ray (the map made by
// buildRequestMap() for a width x height image).
std::int64_t pixelsInTilesWithRequests(const RequestMap& map, int width, int height);

// A well-mixed 64-bit hash (splitmix64's finaliser).
std::uint64_t mixBits(std::uint64_t x);

}  // namespace raycache
