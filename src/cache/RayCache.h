#pragma once
// Per-object ray caching (SPEC §2): the answer to "what does the ray leaving
// object o at point p in direction s bring back?", when an earlier frame
// already traced it.
//
// How a renderer uses it (see examples/cct_minimal for a whole loop):
//
//   RayCache cache(scene, settings);
//   std::vector<CacheWorker> workers = cache.makeWorkers(threadCount);
//   cache.beginFrame(workers);
//   ... in worker w, for pixel i: workers[w].beginPixel(i); then for each
//       secondary ray leaving a caching object o:
//         if (auto color = cache.lookup(o, p, s, workers[w])) use *color;
//         else { color = trace(...); cache.store(o, p, s, color, hitDistance, workers[w]); }
//   FrameCacheStats stats = cache.endFrame(workers);
//
// Determinism: lookups during a frame read the caches as they stood when the
// frame began (stores are only queued); endFrame merges the queued stores in
// a fixed order — by texel, then by (pixel, sequence in the pixel's path) —
// and the first store to an invalid texel wins. Images and cache contents
// therefore do not depend on the thread count or scheduling.
#include <optional>
#include <span>
#include <vector>

#include "cache/CacheStats.h"
#include "cache/CacheWorker.h"
#include "cache/CachingCube.h"
#include "scene/Scene.h"

namespace raycache {

struct RayCacheSettings {
    // Replaces every reflective/refractive object's material setting.
    std::optional<CacheTechnique> techniqueOverride;
    // Replaces every cube's face resolution.
    std::optional<int> resolutionOverride;
    // Benchmark switch: a miss returns black instead of being traced, giving
    // the cost of a frame in which caching objects trace no secondary rays.
    bool ideal = false;
};

class RayCache {
public:
    static constexpr int kMinResolution = 16;
    static constexpr int kMaxResolution = 2048;

    // One cube per object whose (possibly overridden) technique is not None
    // and that reflects or refracts. Throws InputError for a resolution
    // outside [16, 2048] or a technique not implemented yet (CDCT).
    RayCache(const Scene& scene, const RayCacheSettings& settings);

    // The technique `object` is cached with under `settings`: None for objects
    // that neither reflect nor refract. The one rule for which objects get a cube.
    static CacheTechnique techniqueFor(const SceneObject& object, const RayCacheSettings& settings);

    // Throws the InputError the constructor would throw, without allocating
    // any cube: lets callers reject bad settings before doing any work.
    static void validate(const Scene& scene, const RayCacheSettings& settings);

    bool empty() const { return cubes_.empty(); }
    bool cachesObject(int objectId) const { return cubeIndexOf(objectId) >= 0; }
    // The object's cube; the object must be cached.
    const CachingCube& cube(int objectId) const { return cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))].cube; }
    std::size_t bytes() const;
    // Invalidates every texel of every cube.
    void clear();

    std::vector<CacheWorker> makeWorkers(int count) const;
    void beginFrame(std::span<CacheWorker> workers);
    FrameCacheStats endFrame(std::span<CacheWorker> workers);

    // What the ray leaving object `objectId` at `origin` along `direction`
    // brought back in an earlier frame, or nothing if it has to be traced.
    std::optional<Rgb> lookup(int objectId, const Vec3& origin, const Vec3& direction, CacheWorker& worker) const;
    // Queues what a traced ray brought back (`hitDistance` from origin to its
    // first hit, infinity for a miss) for the end of the frame.
    void store(int objectId, const Vec3& origin, const Vec3& direction, const Rgb& color, float hitDistance,
               CacheWorker& worker) const;

private:
    struct Entry {
        int objectId;
        std::string name;
        CachingCube cube;
        double invalidPercentBefore = 100.0;
    };

    int cubeIndexOf(int objectId) const {
        return objectId >= 0 && static_cast<std::size_t>(objectId) < cubeOfObject_.size()
                   ? cubeOfObject_[static_cast<std::size_t>(objectId)]
                   : -1;
    }

    std::vector<Entry> cubes_;
    std::vector<int> cubeOfObject_;  // object id -> index into cubes_, -1 if uncached
    bool ideal_ = false;
};

}  // namespace raycache
