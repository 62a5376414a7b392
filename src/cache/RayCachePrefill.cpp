// RayCache: improved CDCT's pre-fill, whole or spread over frames, and the
// objects whose pre-filled cubes see past their own surface.
#include "cache/RayCache.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/Errors.h"

namespace raycache {

std::vector<int> RayCache::objectsAwaitingPrefill(std::span<const CacheWorker> workers) const {
    std::vector<int> objects;
    // The next change would empty the cubes again (CDCT cubes go whole):
    // pre-filling while the scene moves traced a whole cube per frame.
    if (changedBeforeThisFrame_ && skipStoresReachingChanges_) return objects;
    for (std::size_t c = 0; c < cubes_.size(); ++c) {
        if (!fillsByPrefill(cubes_[c]) || cubes_[c].prefilled) continue;
        const bool asked = std::any_of(workers.begin(), workers.end(),
                                       [&](const CacheWorker& w) { return w.counters_[c].lookups > 0; });
        if (asked) objects.push_back(cubes_[c].objectId);
    }
    return objects;
}

Vec3 RayCache::prefillDirection(int objectId, int texel) const {
    const int n = cube(objectId).size();
    return normalize(cubeTexelCenterDirection(
        CubeTexel{static_cast<CubeFace>(texel / (n * n)), texel % n, (texel / n) % n}, n));
}

void RayCache::completePrefill(int objectId, std::span<const PrefillTexel> texels) {
    Entry& e = cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))];
    if (texels.size() != e.cube.texelCount())
        throw RuntimeError("cache pre-fill of '" + e.name + "': " + std::to_string(texels.size()) + " texels for a cube of " +
                           std::to_string(e.cube.texelCount()));
    e.viewDependentBits.assign((texels.size() + 63) / 64, 0);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        if (texels[i].viewDependent) e.viewDependentBits[i / 64] |= std::uint64_t{1} << (i % 64);
        // As store(): misses and hits beyond maxDepth are cached at maxDepth.
        const float distance = texels[i].hitDistance;
        const float depth = std::isfinite(distance) && distance <= e.cdct.maxDepth ? distance : e.cdct.maxDepth;
        if (!e.cube.writeIfInvalid(static_cast<int>(i), CachingCube::encodeTexel(texels[i].color), depth)) continue;
        ++e.prefilledTexels;
        if (depth < e.cdct.maxDepth) e.farthestSurface = std::max(e.farthestSurface, depth);
    }
    e.prefilled = true;
    // Pre-filled cubes receive no stores, so the pyramid stays current.
    if (improvements_.skipEmptySpace) e.pyramid.emplace(e.cube);
}

std::vector<RayCache::PrefillPiece> RayCache::planPrefill(std::span<const CacheWorker> workers) {
    for (const int objectId : objectsAwaitingPrefill(workers)) {
        Entry& e = cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))];
        if (e.prefillQueued) continue;
        e.prefillQueued = true;
        prefillQueue_.push_back(cubeIndexOf(objectId));
    }
    std::vector<PrefillPiece> pieces;
    std::int64_t left = prefillTexelsPerFrame_;  // 0: no limit
    for (const int c : prefillQueue_) {
        const Entry& e = cubes_[static_cast<std::size_t>(c)];
        const int n = e.cube.size();
        int rows = 6 * n - e.prefillRowsDone;
        if (prefillTexelsPerFrame_ > 0) {
            // Whole rows within what is left; at least one row a frame.
            const std::int64_t fit = left / n;
            if (fit == 0 && !pieces.empty()) break;
            rows = static_cast<int>(std::clamp<std::int64_t>(fit, 1, rows));
            left -= static_cast<std::int64_t>(rows) * n;
        }
        pieces.push_back({e.objectId, e.prefillRowsDone, rows});
        if (prefillTexelsPerFrame_ > 0 && left <= 0) break;
    }
    return pieces;
}

void RayCache::addPrefillRows(int objectId, int firstRow, std::span<const PrefillTexel> texels) {
    const int c = cubeIndexOf(objectId);
    if (c < 0) throw std::logic_error("addPrefillRows: object " + std::to_string(objectId) + " has no cube");
    Entry& e = cubes_[static_cast<std::size_t>(c)];
    const auto n = static_cast<std::size_t>(e.cube.size());
    const int totalRows = 6 * e.cube.size();
    if (firstRow != e.prefillRowsDone || texels.size() % n != 0 ||
        firstRow + static_cast<int>(texels.size() / n) > totalRows)
        throw std::logic_error("addPrefillRows: rows out of order for '" + e.name + "'");
    const int rows = static_cast<int>(texels.size() / n);
    const auto finish = [&](std::span<const PrefillTexel> all) {
        e.prefillRowsDone = 0;
        e.prefillRows = {};
        e.prefillQueued = false;
        prefillQueue_.erase(std::find(prefillQueue_.begin(), prefillQueue_.end(), c));
        completePrefill(objectId, all);
    };
    // A whole cube in one piece needs no copy.
    if (firstRow == 0 && rows == totalRows) return finish(texels);
    if (e.prefillRows.empty()) e.prefillRows.resize(e.cube.texelCount());
    std::copy(texels.begin(), texels.end(), e.prefillRows.begin() + static_cast<std::ptrdiff_t>(firstRow * n));
    e.prefillRowsDone += rows;
    if (e.prefillRowsDone == totalRows) {
        const std::vector<PrefillTexel> all = std::move(e.prefillRows);
        finish(all);
    }
}

std::vector<int> RayCache::objectsSeenPastThemselves() const {
    std::vector<int> objects;
    for (const Entry& e : cubes_)
        if (improvements_.traceOwnSurface && fillsByPrefill(e)) objects.push_back(e.objectId);
    std::sort(objects.begin(), objects.end());
    return objects;
}

}  // namespace raycache
