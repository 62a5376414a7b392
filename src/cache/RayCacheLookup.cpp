// RayCache: the lookups, one ray (lookup) or a batch (lookupBatch). The
// per-ray path (answer, cctAnswer, lookupAnswer, lookupBatchAs) stays in this
// one translation unit so that its calls to one another may be inlined;
// lookupAddressed, the lanes' lookup, is inline in RayCache.h.
#include "cache/RayCache.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace raycache {

std::optional<Rgb> RayCache::answer(const Entry& e, const Vec3& origin, const Vec3& direction,
                                    CacheWorker::Counters& counters) const {
    switch (e.technique) {
    case CacheTechnique::Cdct: {
        // Before its pre-fill the cube holds nothing: the ray is traced.
        if (fillsByPrefill(e) && !e.prefilled) return std::nullopt;
        const CdctResult r = searchCdctImproved(e.cube, e.cdct, improvements_, e.farthestSurface,
                                                e.pyramid ? &*e.pyramid : nullptr, origin, direction);
        counters.countCdctSearch(r.steps);
        if (r.outcome == CdctOutcome::Rejected) ++counters.rejected;
        if (r.outcome != CdctOutcome::Found) return std::nullopt;
        if (improvements_.traceViewDependent && !e.viewDependentBits.empty() &&
            (e.viewDependentBits[static_cast<std::size_t>(r.texel) / 64] >> (r.texel % 64) & 1u)) {
            ++counters.viewDependent;
            return std::nullopt;
        }
        return r.color;
    }
    case CacheTechnique::CdctParity: {
        const CdctResult r = searchCdctParity(e.cube, e.cdct, origin, direction);
        counters.countCdctSearch(r.steps);
        if (r.outcome == CdctOutcome::Found) return r.color;
        return std::nullopt;
    }
    default:
        // CCT addresses by the ray's direction only: what lies along it is taken to be far away.
        return e.cube.read(e.cube.texelIndexFor(direction));
    }
}

std::optional<Rgb> RayCache::lookup(int objectId, const Vec3& origin, const Vec3& direction,
                                    CacheWorker& worker) const {
    if (auto color = lookupAnswer(objectId, origin, direction, worker)) return color;
    if (ideal_ && !bypassed(objectId)) return Rgb{};
    return std::nullopt;
}

std::optional<Rgb> RayCache::lookupAnswer(int objectId, const Vec3& origin, const Vec3& direction,
                                          CacheWorker& worker, bool meetsOwnSurface) const {
    const auto c = static_cast<std::size_t>(cubeIndexOf(objectId));
    CacheWorker::Counters& counters = worker.counters_[c];
    if (!admits(objectId, direction)) {
        ++counters.bypassed;
        return std::nullopt;
    }
    ++counters.lookups;
    if (meetsOwnSurface) ++counters.ownSurface;
    if (oracle_ || meetsOwnSurface) {
        ++counters.misses;
        return std::nullopt;
    }
    if (auto color = answer(cubes_[c], origin, direction, counters)) {
        ++counters.hits;
        ++counters.levelHits[0];
        return color;
    }
    ++counters.misses;
    return std::nullopt;
}

RayCache::CctAnswer RayCache::cctAnswer(const Entry& e, int texel, const Query& q,
                                       CacheWorker::Counters& counters) const {
    const int n = e.cube.size();
    if (e.cube.isValid(texel)) {
        const int inherited = e.cube.inheritedLevels(texel);
        if (inherited == 0) return {0, false};
        // A colour from a texel `inherited` levels coarser answers only a
        // footprint that wide; otherwise the ray is traced and its store
        // replaces the inherited colour.
        if (CoarseLevels::coarsestAllowed(q.spread, levelErrorBound_, n, inherited + 1) == inherited)
            return {inherited, true};
    }
    if (e.coarse.levelCount() <= 1) return {};
    const int coarsest = CoarseLevels::coarsestAllowed(q.spread, levelErrorBound_, n, e.coarse.levelCount());
    if (coarsest == 0) return {};
    const int face = texel / (n * n), y = (texel / n) % n, x = texel % n;
    const float tangent = std::tan(std::clamp(levelErrorBound_ * q.spread, 0.0f, 1.5f));
    bool rejected = false;
    for (int level = 1; level <= coarsest; ++level) {
        const int t = e.coarse.texelOver(face, x, y, level);
        if (!e.coarse.level(level).isValid(t)) continue;
        if (CoarseLevels::seesWithinTangent(e.coarse.seen(level, t), q.origin, q.direction, tangent)) return {level, false};
        rejected = true;
    }
    if (rejected) ++counters.rejected;
    return {};
}

void RayCache::lookupBatch(std::span<const Query> queries, std::span<Rgb> colors, std::span<unsigned char> found,
                           std::span<int> storeTexels, CacheWorker& worker, std::span<int> answerTexels,
                           std::span<std::int8_t> answerLevels) const {
    if (answerLevels.empty())
        lookupBatchAs<false>(queries, colors, found, storeTexels, worker, answerTexels, answerLevels);
    else
        lookupBatchAs<true>(queries, colors, found, storeTexels, worker, answerTexels, answerLevels);
}

template <bool kRecordLevels>
void RayCache::lookupBatchAs(std::span<const Query> queries, std::span<Rgb> colors, std::span<unsigned char> found,
                             std::span<int> storeTexels, CacheWorker& worker, std::span<int> answerTexels,
                             std::span<std::int8_t> answerLevels) const {
    // Chunks small enough for the texel indices to stay on the stack and the
    // prefetched lines to stay in L1/L2 until they are read.
    constexpr std::size_t kChunk = 64;
    // A query of a cube that stands aside this frame, or out of its sample (texel[k]).
    constexpr int kBypassedQuery = -2;
    std::array<int, kChunk> texel;
    for (std::size_t base = 0; base < queries.size(); base += kChunk) {
        const std::size_t count = std::min(kChunk, queries.size() - base);
        for (std::size_t k = 0; k < count; ++k) {
            const Query& q = queries[base + k];
            const Entry& e = cubes_[static_cast<std::size_t>(cubeIndexOf(q.objectId))];
            texel[k] = -1;
            if (e.policy.bypassed()) {
                texel[k] = kBypassedQuery;
                continue;
            }
            if (e.technique != CacheTechnique::Cct) continue;
            texel[k] = q.texel >= 0 ? q.texel : e.cube.texelIndexFor(q.direction);
            if (!e.policy.admitsTexel(texel[k])) {  // out of a sampling cube's sample
                texel[k] = kBypassedQuery;
                continue;
            }
            __builtin_prefetch(e.cube.validWordOf(texel[k]));
        }
        for (std::size_t k = 0; k < count; ++k) {
            if (texel[k] < 0) continue;  // not CCT, or the cube stands aside
            const CachingCube& cube = cubes_[static_cast<std::size_t>(cubeIndexOf(queries[base + k].objectId))].cube;
            if (cube.isValid(texel[k])) __builtin_prefetch(cube.texelWordOf(texel[k]));
        }
        for (std::size_t k = 0; k < count; ++k) {
            const Query& q = queries[base + k];
            const std::size_t i = base + k;
            storeTexels[i] = -1;
            if (!answerTexels.empty()) answerTexels[i] = -1;
            if (texel[k] == kBypassedQuery) {
                // Traced as without a cache; nothing looked up, nothing to store.
                ++worker.counters_[static_cast<std::size_t>(cubeIndexOf(q.objectId))].bypassed;
                if constexpr (kRecordLevels) answerLevels[i] = -1;
                found[i] = 0;
                continue;
            }
            if (texel[k] < 0) {
                const auto color = lookupAnswer(q.objectId, q.origin, q.direction, worker, q.meetsOwnSurface);
                if constexpr (kRecordLevels) answerLevels[i] = color ? 0 : -1;
                found[i] = color || ideal_ ? 1 : 0;
                if (found[i]) colors[i] = color.value_or(Rgb{});
                continue;
            }
            const auto c = static_cast<std::size_t>(cubeIndexOf(q.objectId));
            CacheWorker::Counters& counters = worker.counters_[c];
            ++counters.lookups;
            const Entry& e = cubes_[c];
            if (e.view.fullSize() > 0) ++counters.lookupsByAllowedLevel[static_cast<std::size_t>(
                e.view.levelAllowed(q.spread, levelErrorBound_))];
            const CctAnswer a = oracle_ ? CctAnswer{} : cctAnswer(e, texel[k], q, counters);
            const int level = a.level;
            if constexpr (kRecordLevels) answerLevels[i] = static_cast<std::int8_t>(level);
            if (level >= 0) {
                ++counters.hits;
                ++counters.levelHits[static_cast<std::size_t>(level)];
                // Read while the cube samples only (every texel it looks up is
                // sampled then): the policy keeps the value for its caching frames.
                if (level == 0 && !a.inherited && !e.treeRays.empty() && e.policy.sampling()) {
                    if (const std::uint8_t rays = e.treeRays[static_cast<std::size_t>(texel[k])]) {
                        ++counters.recordedHits;
                        counters.recordedHitRays += rays;
                    }
                }
                colors[i] = level == 0 || a.inherited
                                ? e.cube.readValid(texel[k])
                                : e.coarse.level(level).readValid(e.coarse.texelOver(texel[k], level));
                found[i] = 1;
                // A coarser texel up to a block wide lies within the finest
                // texel's block; an inherited colour's block took the bounds
                // of the block it came from (resizeEntry).
                if (!answerTexels.empty()) answerTexels[i] = a.inherited || (1 << level) <= kBlockSize ? texel[k] : -1;
            } else {
                ++counters.misses;
                found[i] = ideal_ ? 1 : 0;
                if (ideal_) colors[i] = Rgb{};
                else storeTexels[i] = texel[k];
            }
        }
    }
}

}  // namespace raycache
