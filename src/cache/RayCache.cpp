#include "cache/RayCache.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <variant>

#include "core/Errors.h"

namespace raycache {

namespace {

// The ray parameter t >= 0 at which origin + t * direction (unit) is
// `radius` from `center` on the way out; 0 when the ray never gets that far
// inside (it starts outside that sphere and does not come back).
float tAtDistance(const Vec3& center, const Vec3& origin, const Vec3& direction, float radius) {
    const Vec3 w = origin - center;
    const double b = dot(w, direction);
    const double c = static_cast<double>(dot(w, w)) - static_cast<double>(radius) * radius;
    const double t = -b + std::sqrt(std::max(0.0, b * b - c));
    return static_cast<float>(std::max(0.0, t));
}

// The ray parameter at which the line origin + t * direction leaves the box
// center ± half (the far slab crossing); 0 if it is behind the origin.
float tLeavingBox(const Vec3& center, const Vec3& half, const Vec3& origin, const Vec3& direction) {
    float tExit = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) {
        const float d = direction[a];
        if (std::fabs(d) < 1e-12f) continue;  // parallel to this slab pair: it does not bound the exit
        const float t1 = (center[a] - half[a] - origin[a]) / d;
        const float t2 = (center[a] + half[a] - origin[a]) / d;
        tExit = std::min(tExit, std::max(t1, t2));
    }
    return std::isfinite(tExit) ? std::max(0.0f, tExit) : 0.0f;
}

std::string formatNumber(float v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

}  // namespace

CdctParameters RayCache::cdctParametersFor(const SceneObject& object, const RayCacheSettings& settings) {
    CdctParameters p = object.material.cache.cdct;
    if (settings.cdctStepOverride) p.step = *settings.cdctStepOverride;
    if (settings.cdctEpsilonOverride) p.epsilon = *settings.cdctEpsilonOverride;
    if (settings.cdctMaxDepthOverride) p.maxDepth = *settings.cdctMaxDepthOverride;
    return p;
}

void RayCache::validateCdct(const CdctParameters& p, const std::string& what) {
    const auto positive = [&](float v, const char* name) {
        if (!(std::isfinite(v) && v > 0.0f))
            throw InputError(what + ": cdct " + name + " must be a finite number > 0 (got " + formatNumber(v) + ")");
    };
    positive(p.step, "step");
    positive(p.epsilon, "epsilon");
    positive(p.maxDepth, "maxDepth");
    if (!(p.epsilon < p.step))
        throw InputError(what + ": cdct epsilon (" + formatNumber(p.epsilon) + ") must be smaller than step (" +
                         formatNumber(p.step) + ")");
    if (std::ceil(2.0 * p.maxDepth / p.step) > kMaxCdctLinearSteps)
        throw InputError(what + ": cdct step " + formatNumber(p.step) + " is too small for maxDepth " +
                         formatNumber(p.maxDepth) + " (at most 1e6 search steps: step >= maxDepth / 500000)");
}

Vec3 RayCache::boundingHalfSize(const SceneObject& object) {
    Vec3 half;
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
        const Vec3 d = sphere->center - object.origin;
        half =
            Vec3{std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)} + Vec3{sphere->radius, sphere->radius, sphere->radius};
    } else if (const auto* mesh = std::get_if<MeshShape>(&object.shape); mesh && mesh->mesh) {
        for (const Vec3& p : mesh->mesh->positions) {
            const Vec3 d = p - object.origin;
            half = max(half, Vec3{std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
        }
    }
    // A flat object still gets a box of some thickness, and the ray origins,
    // offset slightly off the surface, stay inside it.
    const float extent = std::max({half.x, half.y, half.z, 1e-3f});
    const float margin = 1e-3f * extent;
    return half + Vec3{margin, margin, margin};
}

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
            validateCdct(cdctParametersFor(object, settings), "object '" + object.name + "'");
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
        const CacheTechnique technique = techniqueFor(object, settings);
        if (technique == CacheTechnique::None) continue;
        const int resolution = settings.resolutionOverride.value_or(object.material.cache.faceResolution);
        cubeOfObject_[i] = static_cast<int>(cubes_.size());
        if (technique == CacheTechnique::Cdct)
            cubes_.push_back(Entry{static_cast<int>(i), object.name,
                                   CachingCube(object.origin, resolution, boundingHalfSize(object)),
                                   cdctParametersFor(object, settings)});
        else
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
        if (cubes_[p.cube].cube.writeIfInvalid(p.texel, p.packed, p.depth)) ++stats.objects[p.cube].stores;

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

std::optional<Rgb> RayCache::searchCdct(const Entry& entry, const Vec3& origin, const Vec3& direction) const {
    // Algorithm 4 (thesis §4.5): a linear search along the ray from where its
    // line leaves the box, then a binary search; bounded in both.
    if (!isFinite(origin) || !isFinite(direction) || !(dot(direction, direction) > 0.0f)) return std::nullopt;
    const CachingCube& cube = entry.cube;
    const CdctParameters& p = entry.cdct;
    const Vec3 c = cube.center();
    const Vec3 d = normalize(direction);
    const float tStart = tLeavingBox(c, cube.halfSize(), origin, d);
    // Stored depths never exceed maxDepth, so the point at maxDepth ends the search.
    const float tEnd = std::max(tStart, tAtDistance(c, origin, d, p.maxDepth));
    const double wanted = std::ceil(static_cast<double>(tEnd - tStart) / p.step);
    const double cap = std::ceil(2.0 * p.maxDepth / p.step) + 1.0;
    const int steps = static_cast<int>(std::clamp(wanted, 1.0, cap));

    // The texel addressed by centre -> point at t; -1 if invalid (aborts the search).
    const auto texelAt = [&](float t, float& distance) {
        const Vec3 v = origin + d * t - c;
        distance = length(v);
        const int texel = cube.texelIndexFor(v);
        return cube.isValid(texel) ? texel : -1;
    };

    float previous = tStart;
    for (int i = 1; i <= steps; ++i) {
        const float t = i == steps ? tEnd : tStart + static_cast<float>(i) * p.step;
        float distance;
        const int texel = texelAt(t, distance);
        if (texel < 0) return std::nullopt;
        if (cube.depth(texel) <= distance) {
            // Crossed between `previous` (in front of the stored surface) and t (at or behind it).
            float lo = previous, hi = t;
            int found = texel;
            for (int k = 0; k < kMaxCdctBinarySteps && hi - lo >= p.epsilon; ++k) {
                const float mid = 0.5f * (lo + hi);
                if (!(mid > lo && mid < hi)) break;  // float resolution reached
                const int midTexel = texelAt(mid, distance);
                if (midTexel < 0) return std::nullopt;
                if (cube.depth(midTexel) <= distance) {
                    hi = mid;
                    found = midTexel;
                } else {
                    lo = mid;
                }
            }
            return cube.read(found);
        }
        // Reached maxDepth without crossing (rounding only): what lies there is the environment.
        if (i == steps) return cube.read(texel);
        previous = t;
    }
    return std::nullopt;  // not reached: the last step returns
}

std::optional<Rgb> RayCache::lookup(int objectId, const Vec3& origin, const Vec3& direction,
                                    CacheWorker& worker) const {
    const auto c = static_cast<std::size_t>(cubeIndexOf(objectId));
    CacheWorker::Counters& counters = worker.counters_[c];
    ++counters.lookups;
    const CachingCube& cube = cubes_[c].cube;
    // CCT addresses by the ray's direction only: what lies along it is taken to be far away.
    if (auto color =
            cube.hasDepth() ? searchCdct(cubes_[c], origin, direction) : cube.read(cube.texelIndexFor(direction))) {
        ++counters.hits;
        return color;
    }
    ++counters.misses;
    if (ideal_) return Rgb{};
    return std::nullopt;
}

void RayCache::store(int objectId, const Vec3& origin, const Vec3& direction, const Rgb& color, float hitDistance,
                     CacheWorker& worker) const {
    const auto c = static_cast<std::size_t>(cubeIndexOf(objectId));
    const CachingCube& cube = cubes_[c].cube;
    int texel;
    float depth = CachingCube::kInvalidDepth;
    if (cube.hasDepth()) {
        // CDCT (thesis §4.4): addressed by centre -> hit point P1, holding |P1 - C|.
        // Misses and hits beyond maxDepth become the ray's point at maxDepth
        // from the centre: the point the search ends at for the same ray.
        if (!isFinite(origin) || !isFinite(direction) || !(dot(direction, direction) > 0.0f)) return;
        const Vec3 d = normalize(direction);
        const float maxDepth = cubes_[c].cdct.maxDepth;
        Vec3 toHit = origin + d * hitDistance - cube.center();
        depth = length(toHit);
        if (!(std::isfinite(hitDistance) && depth <= maxDepth)) {
            toHit = origin + d * tAtDistance(cube.center(), origin, d, maxDepth) - cube.center();
            depth = maxDepth;
        }
        if (!isFinite(toHit)) return;
        texel = cube.texelIndexFor(toHit);
    } else {
        texel = cube.texelIndexFor(direction);
    }
    // Lookups read the frame-start state, so only texels invalid then are worth queuing.
    if (cube.isValid(texel)) return;
    // The sequence saturates rather than wrapping; only a path with more than
    // 16 M cached stores could tie, far beyond any depth/weight limit in use.
    constexpr std::uint32_t kMaxSequence = (1u << 24) - 1u;
    const std::uint64_t order = (static_cast<std::uint64_t>(worker.pixel_) << 24) | worker.sequence_;
    if (worker.sequence_ < kMaxSequence) ++worker.sequence_;
    worker.pending_.push_back({order, static_cast<std::uint32_t>(c), texel, CachingCube::encodeTexel(color), depth});
}

}  // namespace raycache
