#pragma once
// Reprojection, the heart of the Render Cache (SPEC §6): every sample is aged,
// evicted past its maximum age, and otherwise moved to where the new camera
// sees it (v' = P'M'v0, the object's current origin plus the sample's offset
// from it). The nearer sample wins a pixel. A sample that loses gets a
// second chance: the nearest of its 8 neighbouring pixels that no sample
// landed in. Without it, samples traced in different frames sit
// at unrelated sub-pixel offsets, pairs of them fall into one pixel beside
// an empty one, and on `room`'s orbit the holes grew to 40 % of the image
// at a budget of 10 % of the pixels per frame. Samples that still win no
// pixel are freed, as on the GPU Render Cache, where samples and pixels
// correspond one to one. (Keeping them while hidden was tried: 8 % fewer
// holes, twice the samples to reproject.)
//
// As on the GPU, the winners are copied into a second pool at their pixel's
// slot (SamplePool): the next frame, the image passes and new samples then
// all go through the pool in pixel order.
//
// How: one pass projects every sample once and bins it by screen tile;
// then each thread resolves whole tiles in a small buffer of packed 64-bit
// keys (depth high, slot low) with a plain compare-min (no atomics, no
// order dependence), gives the tile's losers their second chance there,
// and copies the tile's winners into the other pool. The second chance
// moves a sample one pixel and looks at its landing pixel's 8 neighbours,
// so a tile is resolved with an apron of the samples landing around it:
// the outcome is the same as over the whole image at once. The tile and a
// one-pixel ring around it are then handed, still in cache, to the
// caller's visitor (depth culling, holes and priorities read each pixel's
// 3x3 neighbourhood): a pass over the whole image saved.
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "core/Parallel.h"
#include "rendercache/PointImage.h"
#include "rendercache/SamplePool.h"
#include "rendercache/ScreenProjection.h"
#include "scene/Scene.h"

namespace raycache {

struct ReprojectionCounts {
    std::int64_t placed = 0;   // samples that won a pixel
    std::int64_t moved = 0;    // of those, on a neighbour of the pixel they landed in
    std::int64_t lost = 0;     // behind a nearer sample, past the margin or behind the eye: freed
    std::int64_t evicted = 0;  // too old: freed
    // Wall milliseconds of the two steps: projecting and binning the
    // samples by tile; the tiles' depth tests, second chances, copies and
    // the caller's visitor.
    double binMs = 0.0, resolveMs = 0.0;
};

// Side of the screen tiles reprojection resolves one at a time: a tile's
// z-buffer with its apron, (64 + 6)^2 eight-byte keys = 39 KB, stays in L2
// (Walter et al. 2002 found z-buffering bound by L2 latency and cut
// projection and z-buffering from 42 to 25 ms with a tiled z-buffer).
constexpr int kReprojectionTileSide = 64;

// The depth test's keys: the depth's bits (PointImage::key) above the
// sample's slot, so that the minimum is the nearest sample and equal depths
// go to the lower slot; the depth's sign bit (which no depth sets) marks a
// second-chance offer.
constexpr std::uint64_t kNoReprojectedSample = std::numeric_limits<std::uint64_t>::max();
constexpr std::uint64_t kSecondChanceMark = std::uint64_t{1} << 63;

// A tile whose depth test is finished, handed to reproject()'s caller on
// the thread that resolved it while its keys are in cache.
class ResolvedTile {
public:
    ResolvedTile(const std::uint64_t* keys, std::size_t rowLength, int firstX, int firstY, const TileRange& pixels)
        : keys_(keys), rowLength_(rowLength), firstX_(firstX), firstY_(firstY), pixels_(pixels) {}
    // The tile's pixels, in image coordinates: margin pixels are negative
    // or past the image's edge.
    const TileRange& pixels() const { return pixels_; }
    // As PointImage::keyAt after reprojection, for the tile's pixels and a
    // one-pixel ring around them (x in [x0 - 1, x1], y in [y0 - 1, y1]),
    // pixels past the margin empty.
    std::uint32_t keyAt(int x, int y) const {
        const std::uint64_t key = keys_[static_cast<std::size_t>(y - firstY_) * rowLength_ +
                                        static_cast<std::size_t>(x - firstX_)];
        return key == kNoReprojectedSample ? PointImage::emptyKey()
                                           : static_cast<std::uint32_t>((key & ~kSecondChanceMark) >> 32);
    }

private:
    const std::uint64_t* keys_;
    std::size_t rowLength_;
    int firstX_, firstY_;  // the pixel of keys_[0]
    TileRange pixels_;
};
using ResolvedTileVisitor = std::function<void(const ResolvedTile&)>;

// Kept from frame to frame (fresh memory costs page faults): the samples
// that landed, binned by screen tile, and each worker's tile z-buffer.
struct ReprojectionScratch {
    // A sample that landed: its packed key (depth bits high, source slot
    // low: the minimum is the nearest sample, ties to the lower slot) and
    // its continuous pixel position (the second chance needs the fraction).
    struct Landed {
        std::uint64_t key;
        float x, y;
    };
    // Per (chunk of source slots, tile), chunk * tileCount() + tile: each
    // chunk of the source pool bins its samples into its own lists, so the
    // binning needs neither atomics nor a second pass, and a tile reads the
    // lists of every chunk. A sample within three pixels of a tile's edge
    // is also in the neighbouring tile's list (its apron).
    std::vector<std::vector<Landed>> bins;
    std::vector<std::vector<std::uint64_t>> tileKeys;  // per worker: one tile's z-buffer and apron
    std::vector<std::int32_t> nextPixel;               // per slot of the source pool, see reproject()
    int tilesX = 0, tilesY = 0;                        // of the last reproject()
    int tileCount() const { return tilesX * tilesY; }
};

// Every object's origin, indexed like Scene::objects: a sample's position
// is its offset from its object's origin.
std::vector<Vec3> objectOrigins(const Scene& scene);

// Where sample `slot` of `pool` lands through `projection`, and at what depth;
// false when it lands behind the eye (or absurdly far off the image).
// Misses (SamplePool::kBackground) are infinitely far: their depth is
// +infinity, so any surface wins over them.
// `px`, `py`: the continuous position, whose floor is the pixel.
inline bool projectSample(const SamplePool& pool, std::size_t slot, const std::vector<Vec3>& origins,
                          const ScreenProjection& projection, float& px, float& py, float& depth) {
    const SamplePoint& sample = pool.point[slot];
    const bool background = sample.objectId == SamplePool::kBackground;
    const ScreenProjection::Projected p =
        background ? projection.direction(sample.position)
                   : projection.point(origins[static_cast<std::size_t>(sample.objectId)] + sample.position);
    // Outside this range the conversion to int would overflow.
    constexpr float kFar = 1.0e8f;
    if (!(p.depth > 0.0f && p.x > -kFar && p.x < kFar && p.y > -kFar && p.y < kFar)) return false;
    depth = background ? std::numeric_limits<float>::infinity() : p.depth;
    px = p.x;
    py = p.y;
    return true;
}

inline bool projectSample(const SamplePool& pool, std::size_t slot, const std::vector<Vec3>& origins,
                          const ScreenProjection& projection, int& x, int& y, float& depth) {
    float px, py;
    if (!projectSample(pool, slot, origins, projection, px, py, depth)) return false;
    x = ScreenProjection::pixelOf(px);
    y = ScreenProjection::pixelOf(py);
    return true;
}

// The pixel of a width x height image (y * width + x) where sample `slot`
// lands through `projection`, or -1 when it lands off the image.
inline std::int32_t imagePixelThrough(const SamplePool& pool, std::size_t slot, const std::vector<Vec3>& origins,
                                      const ScreenProjection& projection, int width, int height) {
    int x, y;
    float depth;
    if (!projectSample(pool, slot, origins, projection, x, y, depth) || x < 0 || y < 0 || x >= width || y >= height)
        return -1;
    return y * width + x;
}

// Ages every sample of `from` (its used slots) by one frame, drops those
// older than `maxAge`, gives each pixel of `image` (reset by the caller to
// the new size, and empty) the nearest sample that lands in it, then lets
// the losers try a neighbour, and copies each pixel's winner into `to` at
// the pixel's slot (image.pixelIndex). `to` must have `from`'s capacity and
// image.pixelCount() pixel slots, as `from` must; its pixel slots are all
// written (empty where no sample won), its overflow left unused. `image`
// ends holding each winner's depth (the winner sits at the pixel's slot). `from` is not
// changed. Ties in depth go to the lower slot of `from`: the outcome does
// not depend on the thread count.
// When `next` is given (the predicted camera of the next frame), `nextPixel`
// is resized to `to`'s pixel slots and gets, for each, imagePixelThrough()
// `next` of the sample it now holds (-1 where it holds none): projected
// in the same pass as through `projection`, not in another pass over the pool.
// `tileSide` (>= 1) is the side of the screen tiles the depth test is
// resolved in; the outcome does not depend on it (tests make it small to
// put many samples on tile borders).
// `onTile`, when set, is called once per tile, on any thread, after the
// tile's winners are in `to` and its depths in `image` (its ring's are
// only in the ResolvedTile until every tile is done).
ReprojectionCounts reproject(const SamplePool& from, SamplePool& to, const Scene& scene,
                             const ScreenProjection& projection, int maxAge, PointImage& image,
                             const Parallel& parallel, ReprojectionScratch& scratch,
                             const ScreenProjection* next = nullptr, std::vector<std::int32_t>* nextPixel = nullptr,
                             int tileSide = kReprojectionTileSide, const ResolvedTileVisitor& onTile = {});

}  // namespace raycache
