#include "cache/RayCache.h"

#include <algorithm>

#include "core/Errors.h"

namespace raycache {

CacheTechnique RayCache::techniqueFor(const SceneObject& object, const RayCacheSettings& settings) {
    const Material& m = object.material;
    if (!m.reflects() && !m.refracts()) return CacheTechnique::None;
    return settings.techniqueOverride.value_or(m.cache.technique);
}

void RayCache::validate(const Scene& scene, const RayCacheSettings& settings) {
    if (settings.resolutionOverride &&
        (*settings.resolutionOverride < kMinResolution || *settings.resolutionOverride > kMaxResolution))
        throw InputError("cache resolution must be between " + std::to_string(kMinResolution) + " and " +
                         std::to_string(kMaxResolution) + " (got " + std::to_string(*settings.resolutionOverride) +
                         ")");
    for (const SceneObject& object : scene.objects) {
        const CacheTechnique technique = techniqueFor(object, settings);
        if (technique == CacheTechnique::Cdct)
            throw InputError("object '" + object.name +
                             "': caching technique cdct is not implemented yet; use cct or none (--technique)");
        const int resolution = settings.resolutionOverride.value_or(object.material.cache.faceResolution);
        if (technique != CacheTechnique::None && (resolution < kMinResolution || resolution > kMaxResolution))
            throw InputError("object '" + object.name + "': cache resolution must be between 16 and 2048");
    }
}

RayCache::RayCache(const Scene& scene, const RayCacheSettings& settings) : ideal_(settings.ideal) {
    validate(scene, settings);
    cubeOfObject_.assign(scene.objects.size(), -1);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        if (techniqueFor(object, settings) == CacheTechnique::None) continue;
        const int resolution = settings.resolutionOverride.value_or(object.material.cache.faceResolution);
        cubeOfObject_[i] = static_cast<int>(cubes_.size());
        cubes_.push_back(Entry{static_cast<int>(i), object.name, CachingCube(object.origin, resolution)});
    }
}

std::size_t RayCache::bytes() const {
    std::size_t total = 0;
    for (const Entry& e : cubes_) total += e.cube.bytes();
    return total;
}

void RayCache::clear() {
    for (Entry& e : cubes_) e.cube.clear();
}

std::vector<CacheWorker> RayCache::makeWorkers(int count) const {
    std::vector<CacheWorker> workers(static_cast<std::size_t>(count));
    for (CacheWorker& w : workers) w.counters_.resize(cubes_.size());
    return workers;
}

void RayCache::beginFrame(std::span<CacheWorker> workers) {
    for (Entry& e : cubes_)
        e.invalidPercentBefore =
            100.0 * static_cast<double>(e.cube.texelCount() - e.cube.validCount()) / static_cast<double>(e.cube.texelCount());
    for (CacheWorker& w : workers) {
        w.pending_.clear();
        w.counters_.assign(cubes_.size(), CacheWorker::Counters{});
    }
}

FrameCacheStats RayCache::endFrame(std::span<CacheWorker> workers) {
    std::vector<CacheWorker::PendingStore> pending;
    std::size_t count = 0;
    for (const CacheWorker& w : workers) count += w.pending_.size();
    pending.reserve(count);
    for (const CacheWorker& w : workers) pending.insert(pending.end(), w.pending_.begin(), w.pending_.end());
    // Fixed order: by cube, texel, then the thread-independent (pixel, sequence) key.
    std::sort(pending.begin(), pending.end(), [](const auto& a, const auto& b) {
        if (a.cube != b.cube) return a.cube < b.cube;
        if (a.texel != b.texel) return a.texel < b.texel;
        return a.order < b.order;
    });

    FrameCacheStats stats;
    stats.objects.resize(cubes_.size());
    for (const auto& p : pending)
        if (cubes_[p.cube].cube.writeIfInvalid(p.texel, p.packed)) ++stats.objects[p.cube].stores;

    for (std::size_t c = 0; c < cubes_.size(); ++c) {
        ObjectCacheStats& s = stats.objects[c];
        s.objectId = cubes_[c].objectId;
        s.name = cubes_[c].name;
        s.resolution = cubes_[c].cube.size();
        s.bytes = cubes_[c].cube.bytes();
        s.invalidPercentBefore = cubes_[c].invalidPercentBefore;
        for (const CacheWorker& w : workers) {
            s.lookups += w.counters_[c].lookups;
            s.hits += w.counters_[c].hits;
            s.misses += w.counters_[c].misses;
        }
    }
    for (CacheWorker& w : workers) w.pending_.clear();
    return stats;
}

std::optional<Rgb> RayCache::lookup(int objectId, const Vec3& /*origin*/, const Vec3& direction,
                                    CacheWorker& worker) const {
    // CCT addresses by the ray's direction only: what lies along it is taken to be far away.
    const auto c = static_cast<std::size_t>(cubeIndexOf(objectId));
    CacheWorker::Counters& counters = worker.counters_[c];
    ++counters.lookups;
    const CachingCube& cube = cubes_[c].cube;
    if (auto color = cube.read(cube.texelIndexFor(direction))) {
        ++counters.hits;
        return color;
    }
    ++counters.misses;
    if (ideal_) return Rgb{};
    return std::nullopt;
}

void RayCache::store(int objectId, const Vec3& /*origin*/, const Vec3& direction, const Rgb& color,
                     float /*hitDistance*/, CacheWorker& worker) const {
    const auto c = static_cast<std::size_t>(cubeIndexOf(objectId));
    const CachingCube& cube = cubes_[c].cube;
    const int texel = cube.texelIndexFor(direction);
    // Lookups read the frame-start state, so only texels invalid then are worth queuing.
    if (cube.isValid(texel)) return;
    // The sequence saturates rather than wrapping; only a path with more than
    // 16 M cached stores could tie, far beyond any depth/weight limit in use.
    constexpr std::uint32_t kMaxSequence = (1u << 24) - 1u;
    const std::uint64_t order = (static_cast<std::uint64_t>(worker.pixel_) << 24) | worker.sequence_;
    if (worker.sequence_ < kMaxSequence) ++worker.sequence_;
    worker.pending_.push_back({order, static_cast<std::uint32_t>(c), texel, CachingCube::encodeTexel(color)});
}

}  // namespace raycache
