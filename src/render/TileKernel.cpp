#include "render/TileKernel.h"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>

#include "core/FloatLanes.h"
#include "core/Optics.h"
#include "render/HitLanes.h"
#include "render/StageTimer.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;
constexpr float kKernelInfinity = std::numeric_limits<float>::infinity();

}  // namespace

void TileScratch::beginTile(std::size_t roots) {
    wave.nodes.assign(roots, TileWave::Node{});
    caching.stores.clear();
    caching.trackTrees = false;  // runWaves decides, once it knows the cache
    caching.countTreeRays = false;
    levelRecord.on = false;  // the callers that record say so after this
    visibleFill.roots.clear();
    visibleFill.positions.clear();
}

TileKernel::TileKernel(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                       const RayCache* cache)
    : scene_(scene), tracer_(tracer), settings_(settings), cache_(cache && !cache->empty() ? cache : nullptr),
      shading_(scene), fill_(scene, tracer, cache_), meshShading_(scene) {
    // The cubes' techniques are fixed for the cache's life, so the objects
    // whose lookups test their own surface are known now (kernels are made
    // between frames, when no ray is in flight).
    if (cache_) tracer_.prepareOwnSurfaceTests(cache_->objectsSeenPastThemselves());
}

void TileKernel::renderCameraTile(const CameraRays& cameraRays, const TileRange& tile, std::uint64_t tileKey,
                                  TileScratch& s, CacheWorker* cache, Image& film, CacheLevelImage* levels) const {
    const int tileWidth = tile.x1 - tile.x0;
    const auto n = static_cast<std::size_t>(tileWidth) * static_cast<std::size_t>(tile.y1 - tile.y0);
    s.beginTile(n);
    if (levels) beginLevelRecord(s.levelRecord, n);
    // The film's lines this tile will write, fetched while it traces: the
    // otherwise the pixels' stores miss the cache at the tile's end.
    for (int y = tile.y0; y < tile.y1; ++y) {
        const auto* row = reinterpret_cast<const char*>(&film.at(tile.x0, y));
        const auto* end = reinterpret_cast<const char*>(&film.at(tile.x1 - 1, y) + 1);
        for (const char* line = row; line < end; line += 64) __builtin_prefetch(line, 1, 2);
        if (end > row) __builtin_prefetch(end - 1, 1, 2);
    }
    beginWaves(s, cache);
    traceCameraRaysInLanes(cameraRays, tile, s, cache);
    shadePackets(s, cache && cache_ ? cache : nullptr, false, WaveShadows::OfCameraHits);
    runWaves(s, cache);
    resolveNodes(s, cache, tileKey);
    fillFromVisiblePoints(s, cache, cameraRays.ray(tile.x0, tile.y0).origin);
    StageTimer timer(settings_.stageTimes, s.stages.compose);
    composeTile(s.wave, tile, film);
    if (levels) writeLevelRecord(s.levelRecord, tile, *levels);
}

void TileKernel::renderGBufferTile(const CameraRays& cameraRays, const GBufferView& gbuffer, const TileRange& tile,
                                   std::uint64_t tileKey, TileScratch& s, CacheWorker* cache, Image& film,
                                   CacheLevelImage* levels) const {
    const auto t0 = Clock::now();
    const int tileWidth = tile.x1 - tile.x0;
    const auto n = static_cast<std::size_t>(tileWidth) * static_cast<std::size_t>(tile.y1 - tile.y0);
    s.beginTile(n);
    if (levels) beginLevelRecord(s.levelRecord, n);
    const auto firstBounceBefore = s.firstBounce;
    beginWaves(s, cache);
    readGBufferInLanes(cameraRays, gbuffer, tile, s, cache);
    shadePackets(s, cache && cache_ ? cache : nullptr, /*surfacesKnown=*/true, WaveShadows::OfCameraHits);
    // The G-buffer read, the first hits' shading and the spawn of their rays.
    s.firstBounce += Clock::now() - t0;
    runWaves(s, cache);
    resolveNodes(s, cache, tileKey);
    fillFromVisiblePoints(s, cache, cameraRays.ray(tile.x0, tile.y0).origin);
    const auto t1 = Clock::now();
    {
        StageTimer timer(settings_.stageTimes, s.stages.compose);
        composeTile(s.wave, tile, film);
        if (levels) writeLevelRecord(s.levelRecord, tile, *levels);
    }
    s.compose += Clock::now() - t1;
    // The first bounce was timed as it ran; the rest is the secondary phase.
    s.laterBounces += (t1 - t0) - (s.firstBounce - firstBounceBefore);
}

void TileKernel::renderFromInside(int objectId, std::span<const Ray> rays, int depth,
                                  std::span<RayCache::PrefillTexel> out, TileScratch& s) const {
    // Enough for any closed mesh a cube centre sits in; past this the ray
    // counts as seeing the environment.
    constexpr int kMaxOwnSurfaces = 64;
    const std::size_t n = rays.size();
    s.beginTile(n);
    beginWaves(s, nullptr);
    {
        StageTimer timer(settings_.stageTimes, s.stages.firstHits);
        beginFirstHits(s, n);
        for (std::size_t i = 0; i < n; ++i) {
            ++s.counts.prefill;
            Ray r = rays[i];
            out[i].viewDependent = 0;
            out[i].hitDistance = kKernelInfinity;
            bool shaded = false;
            for (int k = 0; k < kMaxOwnSurfaces; ++k) {
                const TraceHit hit = tracer_.intersect(r);
                if (!hit.hit()) break;
                if (hit.objectId != objectId) {
                    out[i].hitDistance = hit.t;
                    const Material& seen = scene_.objects[static_cast<std::size_t>(hit.objectId)].material;
                    out[i].viewDependent = seen.reflects() || seen.refracts() ? 1 : 0;
                    addFirstHit(s, r, hit, static_cast<int>(i), depth, RayCone{});
                    shaded = true;
                    break;
                }
                r.tNear = hit.t + surfaceOffset(r.origin + r.direction * hit.t);
            }
            if (!shaded) s.wave.nodes[i].direct = shading_.background(rays[i]);
        }
        endFirstHits(s);
    }
    shadePackets(s, nullptr, false, WaveShadows::Traced);
    runWaves(s, nullptr);
    resolveNodes(s, nullptr, 0);
    for (std::size_t i = 0; i < n; ++i) out[i].color = s.wave.nodes[i].color();
}

void TileKernel::renderCameraPixels(const CameraRays& cameraRays, std::span<const PixelCoord> pixels,
                                    std::uint64_t batchKey, TileScratch& s, CacheWorker* cache,
                                    std::span<PrimarySample> out) const {
    const std::size_t n = pixels.size();
    s.beginTile(n);
    s.renderCache.recordFirstHits = true;
    s.renderCache.rootViewIndependent.assign(n, Rgb{});
    s.renderCache.rootLighting.assign(n, Rgb{});
    s.renderCache.rootLitMask.assign(n, 0);
    beginWaves(s, cache);
    {
        StageTimer timer(settings_.stageTimes, s.stages.firstHits);
        s.batch.rays.resize(n);
        s.batch.hits.resize(n);
        for (std::size_t i = 0; i < n; ++i) s.batch.rays[i] = cameraRays.ray(pixels[i].x, pixels[i].y);
        tracer_.intersectPrimary(std::span(s.batch.rays.data(), n), std::span(s.batch.hits.data(), n));
        s.counts.primary += n;
        const RayCone pixel{0.0f, cameraRays.pixelSpread()};
        beginFirstHits(s, n);
        for (std::size_t i = 0; i < n; ++i) {
            out[i].hit = s.batch.hits[i];
            if (s.batch.hits[i].hit())
                addFirstHit(s, s.batch.rays[i], s.batch.hits[i], static_cast<int>(i), 1, pixel);
            else
                s.wave.nodes[i].direct = shading_.background(s.batch.rays[i]);
        }
        endFirstHits(s);
    }
    shadePackets(s, cache && cache_ ? cache : nullptr, false, WaveShadows::OfCameraHits);
    s.renderCache.recordFirstHits = false;
    runWaves(s, cache);
    resolveNodes(s, cache, batchKey);
    for (std::size_t i = 0; i < n; ++i) {
        out[i].color = s.wave.nodes[i].color();
        out[i].viewIndependent = s.renderCache.rootViewIndependent[i];
        out[i].lighting = s.renderCache.rootLighting[i];
        out[i].litMask = s.renderCache.rootLitMask[i];
    }
}

void TileKernel::reshadeSurfaces(std::span<const ReshadeRequest> requests, std::uint64_t batchKey, TileScratch& s,
                                 CacheWorker* cache, std::span<Rgb> out) const {
    const std::size_t n = requests.size();
    s.beginTile(n);
    s.renderCache.reshade = requests;
    beginWaves(s, cache);
    beginFirstHits(s, n);
    for (std::size_t i = 0; i < n; ++i)
        addFirstHit(s, requests[i].ray, requests[i].hit, static_cast<int>(i), 1, RayCone{});
    endFirstHits(s);
    shadePackets(s, cache && cache_ ? cache : nullptr, false, WaveShadows::Known);
    s.renderCache.reshade = {};
    runWaves(s, cache);
    resolveNodes(s, cache, batchKey);
    for (std::size_t i = 0; i < n; ++i) out[i] = s.wave.nodes[i].color();
}

void TileKernel::renderRays(std::span<const RayTreeRecord> rays, std::span<Rgb> out, TileScratch& s) const {
    const std::size_t n = rays.size();
    s.beginTile(n);
    s.wave.pending.clear();
    for (std::size_t i = 0; i < n; ++i)
        s.wave.pending.push_back({Ray{rays[i].origin, rays[i].direction}, static_cast<int>(i), rays[i].pathWeight,
                                  rays[i].depth, TileWave::Kind::Reflection});
    beginWaves(s, nullptr);
    runWaves(s, nullptr);
    resolveNodes(s, nullptr, 0);
    for (std::size_t i = 0; i < n; ++i) out[i] = s.wave.nodes[i].color();
}

void TileKernel::beginWaves(TileScratch& s, CacheWorker* cache) const {
    s.caching.trackTrees = cache && cache_ && cache_->tracksDependencies();
    s.caching.countTreeRays = cache && cache_;
    // Bounds are kept for tracked nodes only, which emitSecondaryRay makes
    // and resets one by one: the camera rays' nodes (most of a tile's) are
    // never tracked, and clearing a bounds record for each of them showed
    // in profiles of animated scenes.
    if (s.caching.trackTrees && s.caching.nodeBounds.size() < s.wave.nodes.size())
        s.caching.nodeBounds.resize(s.wave.nodes.size());
}

void TileKernel::runWaves(TileScratch& s, CacheWorker* cache) const {
    CacheWorker* const useCache = cache && cache_ ? cache : nullptr;
    if (useCache) lookupReuse(s, *useCache);
    while (!s.wave.pending.empty()) {
        traceSecondaryRaysInLanes(s);
        shadePackets(s, useCache, false, WaveShadows::Traced);
        if (useCache) lookupReuse(s, *useCache);
    }
}

void TileKernel::lookupReuse(TileScratch& s, CacheWorker& cache) const {
    StageTimer timer(settings_.stageTimes, s.stages.reuseLookups);
    TileCacheBookkeeping& caching = s.caching;
    const std::size_t n = caching.leaving.size();
    if (n == 0) return;
    caching.cachedColors.resize(n);
    caching.cacheFound.resize(n);
    caching.storeTexels.resize(n);
    caching.answerTexels.resize(caching.trackTrees ? n : 0);
    // Without the cache-level record the batch is looked up exactly as before:
    // an empty span, and one branch here and one after.
    std::span<std::int8_t> answerLevels;
    if (s.levelRecord.on) {
        s.levelRecord.answerLevels.resize(n);
        answerLevels = s.levelRecord.answerLevels;
    }
    cache_->lookupBatch(caching.cacheQueries, caching.cachedColors, caching.cacheFound, caching.storeTexels, cache,
                        caching.answerTexels, answerLevels);
    if (s.levelRecord.on) recordLookupLevels(s);
    for (std::size_t i = 0; i < n; ++i) {
        const TileCacheBookkeeping::LeavingRay& l = caching.leaving[i];
        const RayCache::Query& q = caching.cacheQueries[i];
        TileWave::Node& node = s.wave.nodes[static_cast<std::size_t>(l.node)];
        if (caching.cacheFound[i]) {
            node.direct = caching.cachedColors[i];
            // The answer stands for another tree: whatever it depended on, this
            // one does. Only a tree that is stored asks (the answered node's
            // bounds go nowhere unless its parent's do).
            if (caching.trackTrees && s.wave.nodes[static_cast<std::size_t>(node.parent)].tracked)
                cache_->addAnswerDependencies(q.objectId, caching.answerTexels[i],
                                              caching.nodeBounds[static_cast<std::size_t>(l.node)]);
            continue;
        }
        queueMissedLeavingRay(s, q.objectId, caching.storeTexels[i],
                              {Ray{q.origin, q.direction}, l.node, l.pathWeight, l.depth, l.kind, l.cone});
    }
}

void TileKernel::queueMissedLeavingRay(TileScratch& s, int objectId, int texel, const TileWave::PendingRay& ray) {
    s.wave.nodes[static_cast<std::size_t>(ray.node)].store = static_cast<int>(s.caching.stores.size());
    s.caching.stores.push_back({objectId, texel, ray.ray.origin, ray.ray.direction, 0.0f, ray.depth, ray.pathWeight});
    s.wave.pending.push_back(ray);
}

void TileKernel::beginLevelRecord(TileCacheLevelRecord& record, std::size_t roots) {
    record.on = true;
    record.rootLevels.assign(roots, CacheLevelImage::kNoCachingRay);
    record.rootLevelWeights.assign(roots, 0.0f);
}

void TileKernel::recordLookupLevels(TileScratch& s) {
    const std::vector<TileCacheBookkeeping::LeavingRay>& leaving = s.caching.leaving;
    const std::vector<std::int8_t>& answerLevels = s.levelRecord.answerLevels;
    for (std::size_t i = 0; i < leaving.size(); ++i)
        noteRootLevel(s, leaving[i].node, leaving[i].pathWeight,
                      answerLevels[i] >= 0 ? answerLevels[i] : CacheLevelImage::kTraced);
}

void TileKernel::noteRootLevel(TileScratch& s, int node, float pathWeight, std::int8_t level) {
    // The pixel is the root of the ray's tree: a few parents up (at most maxDepth).
    const std::vector<TileWave::Node>& nodes = s.wave.nodes;
    int root = node;
    while (nodes[static_cast<std::size_t>(root)].parent >= 0) root = nodes[static_cast<std::size_t>(root)].parent;
    const auto r = static_cast<std::size_t>(root);
    // The weightiest lookup stays; on equal weight the one asked first
    // (an earlier wave, or earlier in this batch). See CacheLevelImage.
    TileCacheLevelRecord& record = s.levelRecord;
    if (record.rootLevels[r] != CacheLevelImage::kNoCachingRay && !(pathWeight > record.rootLevelWeights[r])) return;
    record.rootLevels[r] = level;
    record.rootLevelWeights[r] = pathWeight;
}

void TileKernel::composeTile(const TileWave& wave, const TileRange& tile, Image& film) {
    // Row by row: no division per pixel to find its place.
    std::size_t root = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x, ++root) film.at(x, y) = wave.nodes[root].color();
}

void TileKernel::writeLevelRecord(const TileCacheLevelRecord& record, const TileRange& tile, CacheLevelImage& levels) {
    const int tileWidth = tile.x1 - tile.x0;
    for (std::size_t i = 0; i < record.rootLevels.size(); ++i)
        levels.at(tile.x0 + static_cast<int>(i) % tileWidth, tile.y0 + static_cast<int>(i) / tileWidth) =
            record.rootLevels[i];
}

void TileKernel::recordTracedRay(TileScratch& s, const TileWave::PendingRay& ray, bool hit, float t) const {
    if (ray.kind == TileWave::Kind::Reflection) ++s.counts.reflection;
    else ++s.counts.refraction;
    TileWave::Node& node = s.wave.nodes[static_cast<std::size_t>(ray.node)];
    ++node.tracedRays;
    if (node.store >= 0) s.caching.stores[static_cast<std::size_t>(node.store)].hitDistance = hit ? t : kKernelInfinity;
    if (node.tracked) {
        RayTreeBounds& bounds = s.caching.nodeBounds[static_cast<std::size_t>(ray.node)];
        if (hit) bounds.addSegment(ray.ray.origin, ray.ray.origin + ray.ray.direction * t);
        else bounds.addEscape(ray.ray.origin, ray.ray.direction);
    }
    if (!hit) node.direct = shading_.background(ray.ray);
}

void TileKernel::resolveNodes(TileScratch& s, CacheWorker* cache, std::uint64_t tileKey) const {
    StageTimer timer(settings_.stageTimes, s.stages.resolve);
    if (cache) cache->beginBatch(tileKey);
    // Nodes are created after their parents, so walking backwards finishes
    // every node's colour before it is stored or passed up. The roots come
    // first (beginTile), so the first root met ends the walk.
    for (std::size_t i = s.wave.nodes.size(); i-- > 0;) {
        const TileWave::Node& node = s.wave.nodes[i];
        if (node.parent < 0) break;
        const Rgb color = node.color();
        if (node.store >= 0 && cache) {
            const TileCacheBookkeeping::NodeStore& st = s.caching.stores[static_cast<std::size_t>(node.store)];
            std::optional<RayTreeRecord> tree;
            if (s.caching.trackTrees)
                tree = RayTreeRecord{s.caching.nodeBounds[i], st.origin, st.direction, st.depth, st.pathWeight};
            cache_->store(st.objectId, st.origin, st.direction, color, st.hitDistance, *cache, st.storeTexel,
                          tree ? &*tree : nullptr, node.tracedRays);
        }
        s.wave.nodes[static_cast<std::size_t>(node.parent)].tracedRays += node.tracedRays;
        if (s.wave.nodes[static_cast<std::size_t>(node.parent)].tracked)
            s.caching.nodeBounds[static_cast<std::size_t>(node.parent)].add(s.caching.nodeBounds[i]);
        s.wave.nodes[static_cast<std::size_t>(node.parent)].secondary += color * node.weightInParent;
    }
}

void TileKernel::noteVisiblePoint(TileScratch& s, int root, int objectId, const Vec3& position) const {
    if (!fill_.fills(scene_.objects[static_cast<std::size_t>(objectId)].material)) return;
    s.visibleFill.roots.push_back(root);
    s.visibleFill.positions.push_back(position);
}

void TileKernel::fillFromVisiblePoints(TileScratch& s, CacheWorker* cache, const Vec3& eye) const {
    TileVisibleFill& fill = s.visibleFill;
    if (!cache || fill.roots.empty()) return;
    StageTimer timer(settings_.stageTimes, s.stages.visibleFill);
    fill.points.resize(fill.roots.size());
    for (std::size_t k = 0; k < fill.roots.size(); ++k)
        fill.points[k] = {fill.positions[k], s.wave.nodes[static_cast<std::size_t>(fill.roots[k])].color()};
    s.counts.fill += fill_.fillTile(fill.points, eye, fill.scratch, *cache);
}

}  // namespace raycache
