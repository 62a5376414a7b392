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
    const int object = pool.objectId[slot];
    const bool background = object == SamplePool::kBackground;
    const ScreenProjection::Projected p =
        background ? projection.direction(pool.position[slot])
                   : projection.point(origins[static_cast<std::size_t>(object)] + pool.position[slot]);
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
    x = static_cast<int>(std::floor(px));
    y = static_cast<int>(std::floor(py));
    return true;
}

// Ages every sample by one frame and frees those older than `maxAge`,
// offers the rest to `image` (reset by the caller to the new size), frees
// those that win no pixel and sets shown[slot] (resized to the pool) for the
// winners. The outcome does not depend on the thread count.
// `scratch`, when given, is reused from frame to frame (no allocation).
ReprojectionCounts reproject(SamplePool& pool, const Scene& scene, const ScreenProjection& projection, int maxAge,
                             PointImage& image, std::vector<unsigned char>& shown, const Parallel& parallel,
                             std::vector<unsigned char>* scratch = nullptr);

}  // namespace raycache
