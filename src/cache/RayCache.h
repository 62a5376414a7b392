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
#include <string>
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
    // Replace every CDCT object's search parameters (CdctParameters, Material.h).
    std::optional<float> cdctStepOverride;
    std::optional<float> cdctEpsilonOverride;
    std::optional<float> cdctMaxDepthOverride;
    // Benchmark switch: a miss returns black instead of being traced, giving
    // the cost of a frame in which caching objects trace no secondary rays.
    bool ideal = false;
};

class RayCache {
public:
    static constexpr int kMinResolution = 16;
    static constexpr int kMaxResolution = 2048;
    // CDCT: the linear search takes at most ceil(2 * maxDepth / step) steps;
    // parameters asking for more than this are rejected.
    static constexpr double kMaxCdctLinearSteps = 1e6;
    // CDCT: the binary search halves its interval at most this many times.
    static constexpr int kMaxCdctBinarySteps = 64;

    // One cube per object whose (possibly overridden) technique is not None
    // and that reflects or refracts; CDCT cubes get a box bounding the object
    // around its origin. Throws InputError for a resolution outside
    // [16, 2048] or invalid CDCT parameters.
    RayCache(const Scene& scene, const RayCacheSettings& settings);

    // The technique `object` is cached with under `settings`: None for objects
    // that neither reflect nor refract. The one rule for which objects get a cube.
    static CacheTechnique techniqueFor(const SceneObject& object, const RayCacheSettings& settings);
    // The CDCT search parameters of `object` under `settings`.
    static CdctParameters cdctParametersFor(const SceneObject& object, const RayCacheSettings& settings);
    // Throws InputError unless every parameter is finite and > 0, epsilon <
    // step and the linear search stays within kMaxCdctLinearSteps. `what`
    // prefixes the message.
    static void validateCdct(const CdctParameters& parameters, const std::string& what);
    // Half-extent per axis of the axis-aligned box centred on the object's
    // origin that bounds its geometry (every component > 0).
    static Vec3 boundingHalfSize(const SceneObject& object);

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
    // CCT reads the texel addressed by `direction`; CDCT searches the depths
    // along the ray (docs/caching.md), in a bounded number of steps.
    std::optional<Rgb> lookup(int objectId, const Vec3& origin, const Vec3& direction, CacheWorker& worker) const;
    // Queues what a traced ray brought back (`hitDistance` from origin to its
    // first hit, infinity for a miss) for the end of the frame. CDCT stores
    // it at the texel addressed by centre -> hit point, with that distance
    // (misses and hits beyond maxDepth: the point of the ray at maxDepth).
    void store(int objectId, const Vec3& origin, const Vec3& direction, const Rgb& color, float hitDistance,
               CacheWorker& worker) const;

private:
    struct Entry {
        int objectId;
        std::string name;
        CachingCube cube;
        CdctParameters cdct;  // used by CDCT cubes (cube.hasDepth())
        double invalidPercentBefore = 100.0;
    };

    std::optional<Rgb> searchCdct(const Entry& entry, const Vec3& origin, const Vec3& direction) const;

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
