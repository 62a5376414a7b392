#pragma once
// Reprojection, the heart of the Render Cache (Walter et al. 1999): every sample is aged,
// evicted past its maximum age, and otherwise moved to where the new camera
// sees it (v' = P'M'v0, the object's current origin plus the sample's offset
// from it). The nearer sample wins a pixel. A sample that loses gets a
// second chance: the nearest of its 8 neighbouring pixels that no sample
// landed in. Without it, samples traced in different frames sit
// at unrelated sub-pixel offsets, pairs of them fall into one pixel beside
// an empty one, and on a moving camera the holes grow to a large share of
// the image. Samples that still win no
// pixel are freed, as on the GPU Render Cache, where samples and pixels
// correspond one to one. (Keeping them while hidden was tried: a few
// holes fewer for twice the samples to reproject.)
//
// As on the GPU, the winners are copied into a second pool at their pixel's
// slot (SamplePool): the next frame, the image passes and new samples then
// all go through the pool in pixel order.
#include <cmath>
#include <cstdint>
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
    // What the passes touched (rendercache/ReconstructionBytes.h).
    std::int64_t live = 0;             // samples in `from`'s used slots: placed + lost + evicted
    std::int64_t offered = 0;          // offered to a pixel in the first round (landed in the image or margin)
    std::int64_t farOffers = 0;        // of those, tested on one thread (landed far from their band)
    std::int64_t secondChances = 0;    // first-round losers, each offered a neighbour
    std::int64_t reshadeCopied = 0;    // winners whose ReshadeInputs were copied (they depend on the eye)
    std::int64_t texturingCopied = 0;  // winners whose SampleTexturing was copied (textured)
};

// Kept from frame to frame (fresh memory costs page faults): per band of
// rows, the samples that landed too far from it to be tested in parallel,
// and the samples that lost the first round with where they landed (only
// they get a second chance, so only they are visited again, and their
// projection is not repeated). Keeping every sample's landing instead cost
// more in writes than projecting the displaced losers again.
struct ReprojectionScratch {
    struct Landed {
        std::uint32_t slot;  // in the source pool
        float x, y;          // continuous pixel position
        float depth;
    };
    std::vector<std::vector<Landed>> far;     // per band
    std::vector<std::vector<Landed>> losers;  // per band, then those of the offers made on one thread
    std::vector<std::int32_t> nextPixel;      // per slot of the source pool, see reproject()
    std::vector<std::uint32_t> winner;        // per pixel: the source slot holding it in the depth test
};

// Every object's origin, indexed like Scene::objects: a sample's position
// is its offset from its object's origin.
std::vector<Vec3> objectOrigins(const Scene& scene);

// Where sample `slot` of `pool` lands through `projection`, and at what depth;
// false when it lands behind the eye (or absurdly far off the image).
// Misses (SamplePool::kBackground) are infinitely far: their depth is
// +infinity, so any surface wins over them.
// `px`, `py`: the continuous position, whose floor is the pixel.
inline bool projectPoint(const SamplePoint& sample, const Vec3* origins, const ScreenProjection& projection,
                         float& px, float& py, float& depth) {
    const bool background = sample.objectId == SamplePool::kBackground;
    const ScreenProjection::Projected p =
        background ? projection.direction(sample.position)
                   : projection.point(origins[static_cast<std::size_t>(sample.objectId)] + sample.position);
    constexpr float kFar = ScreenProjection::kRange;
    if (!(p.depth > 0.0f && p.x > -kFar && p.x < kFar && p.y > -kFar && p.y < kFar)) return false;
    depth = background ? std::numeric_limits<float>::infinity() : p.depth;
    px = p.x;
    py = p.y;
    return true;
}

inline bool projectSample(const SamplePool& pool, std::size_t slot, const std::vector<Vec3>& origins,
                          const ScreenProjection& projection, float& px, float& py, float& depth) {
    return projectPoint(pool.point[slot], origins.data(), projection, px, py, depth);
}

// imagePixelThrough() for a sample given by its point.
inline std::int32_t imagePixelOf(const SamplePoint& sample, const Vec3* origins, const ScreenProjection& projection,
                                 int width, int height) {
    float px, py, depth;
    if (!projectPoint(sample, origins, projection, px, py, depth)) return -1;
    const int x = ScreenProjection::pixelOf(px), y = ScreenProjection::pixelOf(py);
    if (x < 0 || y < 0 || x >= width || y >= height) return -1;
    return y * width + x;
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

// Ages every sample of `from` (its used slots) by `ageStep` (one frame;
// the asynchronous mode ages by the sample requests completed since the
// last display frame, so samples do not age while no new ones come), drops those
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
ReprojectionCounts reproject(const SamplePool& from, SamplePool& to, const Scene& scene,
                             const ScreenProjection& projection, int maxAge, PointImage& image,
                             const Parallel& parallel, ReprojectionScratch& scratch,
                             const ScreenProjection* next = nullptr, std::vector<std::int32_t>* nextPixel = nullptr,
                             int ageStep = 1);

}  // namespace raycache
