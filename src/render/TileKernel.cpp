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
    nodes.assign(roots, Node{});
    stores.clear();
    trackTrees = false;  // runWaves decides, once it knows the cache
    countTreeRays = false;
    recordLevels = false;  // the callers that record say so after this
    vertices.clear();
    surfaces.clear();
    albedo.clear();
    fillRoots.clear();
    fillPositions.clear();
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
    if (levels) beginLevelRecord(s, n);
    // The film's lines this tile will write, fetched while it traces: the
    // pixels' stores missed the cache, 4 % of grid-32's ideal frame.
    for (int y = tile.y0; y < tile.y1; ++y) {
        const auto* row = reinterpret_cast<const char*>(&film.at(tile.x0, y));
        const auto* end = reinterpret_cast<const char*>(&film.at(tile.x1 - 1, y) + 1);
        for (const char* line = row; line < end; line += 64) __builtin_prefetch(line, 1, 2);
        if (end > row) __builtin_prefetch(end - 1, 1, 2);
    }
    if (tracesCameraRaysInLanes()) {
        beginWaves(s, cache);
        traceCameraRaysInLanes(cameraRays, tile, s, cache);
        shadePackets(s, cache && cache_ ? cache : nullptr);
        runWaves(s, cache, FirstWave::Spawned, true);
    } else {
        traceCameraTile(cameraRays, tile, s, cache);
        runWaves(s, cache, FirstWave::Hits, true);
    }
    resolveNodes(s, cache, tileKey);
    fillFromVisiblePoints(s, cache, cameraRays.ray(tile.x0, tile.y0).origin);
    StageTimer timer(settings_.stageTimes, s.stages.compose);
    composeTile(s, tile, film);
    if (levels) writeLevelRecord(s, tile, *levels);
}

void TileKernel::traceCameraTile(const CameraRays& cameraRays, const TileRange& tile, TileScratch& s,
                                 CacheWorker* cache) const {
    StageTimer timer(settings_.stageTimes, s.stages.firstHits);
    const auto n = s.nodes.size();
    s.rays.resize(n);
    s.hits.resize(n);
    std::size_t i = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1;) {
            const int count = std::min(kFloatLanes, tile.x1 - x);
            cameraRays.rowOfRays(x, y, count, s.rays.data() + i);
            x += count;
            i += static_cast<std::size_t>(count);
        }
    tracer_.intersectPrimary(std::span(s.rays.data(), n), std::span(s.hits.data(), n));
    s.counts.primary += n;
    const RayCone pixel{0.0f, cameraRays.pixelSpread()};
    for (i = 0; i < n; ++i) {
        if (s.hits[i].hit()) {
            s.vertices.push_back({s.rays[i], s.hits[i], static_cast<int>(i), 1.0f, 1, pixel});
            if (cache && fill_.active())
                noteVisiblePoint(s, static_cast<int>(i), s.hits[i].objectId,
                                 s.rays[i].origin + s.rays[i].direction * s.hits[i].t);
        } else {
            s.nodes[i].direct = shading_.background(s.rays[i]);
        }
    }
}

void TileKernel::renderGBufferTile(const CameraRays& cameraRays, const GBufferView& gbuffer, const TileRange& tile,
                                   std::uint64_t tileKey, TileScratch& s, CacheWorker* cache, Image& film,
                                   CacheLevelImage* levels) const {
    const auto t0 = Clock::now();
    const int tileWidth = tile.x1 - tile.x0;
    const auto n = static_cast<std::size_t>(tileWidth) * static_cast<std::size_t>(tile.y1 - tile.y0);
    s.beginTile(n);
    if (levels) beginLevelRecord(s, n);
    const auto firstBounceBefore = s.firstBounce;
    if (tracesCameraRaysInLanes()) {
        beginWaves(s, cache);
        readGBufferInLanes(cameraRays, gbuffer, tile, s, cache);
        shadePackets(s, cache && cache_ ? cache : nullptr, /*surfacesKnown=*/true);
        // The G-buffer read, the first hits' shading and the spawn of their rays.
        s.firstBounce += Clock::now() - t0;
        runWaves(s, cache, FirstWave::Spawned, true);
    } else {
        readGBufferTile(cameraRays, gbuffer, tile, s, cache);
        s.firstBounce += Clock::now() - t0;  // reading the G-buffer belongs to the first bounce
        runWaves(s, cache, FirstWave::Surfaces, true);
    }
    resolveNodes(s, cache, tileKey);
    fillFromVisiblePoints(s, cache, cameraRays.ray(tile.x0, tile.y0).origin);
    const auto t1 = Clock::now();
    {
        StageTimer timer(settings_.stageTimes, s.stages.compose);
        composeTile(s, tile, film);
        if (levels) writeLevelRecord(s, tile, *levels);
    }
    s.compose += Clock::now() - t1;
    // The first bounce was timed as it ran; the rest is the secondary phase.
    s.laterBounces += (t1 - t0) - (s.firstBounce - firstBounceBefore);
}

void TileKernel::readGBufferTile(const CameraRays& cameraRays, const GBufferView& gbuffer, const TileRange& tile,
                                 TileScratch& s, CacheWorker* cache) const {
    {
        StageTimer timer(settings_.stageTimes, s.stages.firstHits);
        const RayCone pixel{0.0f, cameraRays.pixelSpread()};
        std::size_t k = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x, ++k) {
                const std::size_t i = gbuffer.index(x, y);
                const Ray ray = cameraRays.ray(x, y);
                if (!gbuffer.hasSurface(i)) {
                    s.nodes[k].direct = shading_.background(ray);
                    continue;
                }
                TraceHit hit;
                hit.objectId = gbuffer.objectId(i);
                hit.primitiveId = gbuffer.primitiveId(i);
                s.surfaces.push_back(surfacePointFromGBuffer(scene_, gbuffer, i, ray.direction));
                hit.t = length(s.surfaces.back().position - ray.origin);
                s.vertices.push_back({ray, hit, static_cast<int>(k), 1.0f, 1, pixel});
                s.albedo.push_back(gbuffer.albedoAt(i));
                if (cache && fill_.active())
                    noteVisiblePoint(s, static_cast<int>(k), hit.objectId, s.surfaces.back().position);
            }
    }
}

void TileKernel::renderFromInside(int objectId, std::span<const Ray> rays, int depth,
                                  std::span<RayCache::PrefillTexel> out, TileScratch& s) const {
    // Enough for any closed mesh a cube centre sits in; past this the ray
    // counts as seeing the environment.
    constexpr int kMaxOwnSurfaces = 64;
    const std::size_t n = rays.size();
    s.beginTile(n);
    s.rootHitDistance.assign(n, kKernelInfinity);
    {
        StageTimer timer(settings_.stageTimes, s.stages.firstHits);
        for (std::size_t i = 0; i < n; ++i) {
            ++s.counts.prefill;
            Ray r = rays[i];
            out[i].viewDependent = 0;
            bool shaded = false;
            for (int k = 0; k < kMaxOwnSurfaces; ++k) {
                const TraceHit hit = tracer_.intersect(r);
                if (!hit.hit()) break;
                if (hit.objectId != objectId) {
                    s.rootHitDistance[i] = hit.t;
                    const Material& seen = scene_.objects[static_cast<std::size_t>(hit.objectId)].material;
                    out[i].viewDependent = seen.reflects() || seen.refracts() ? 1 : 0;
                    s.vertices.push_back({r, hit, static_cast<int>(i), 1.0f, depth});
                    shaded = true;
                    break;
                }
                r.tNear = hit.t + surfaceOffset(r.origin + r.direction * hit.t);
            }
            if (!shaded) s.nodes[i].direct = shading_.background(rays[i]);
        }
    }
    runWaves(s, nullptr, FirstWave::Hits, false);
    resolveNodes(s, nullptr, 0);
    for (std::size_t i = 0; i < n; ++i) {
        out[i].color = s.nodes[i].color();
        out[i].hitDistance = s.rootHitDistance[i];
    }
}

void TileKernel::renderCameraPixels(const CameraRays& cameraRays, std::span<const PixelCoord> pixels,
                                    std::uint64_t batchKey, TileScratch& s, CacheWorker* cache,
                                    std::span<PrimarySample> out) const {
    const std::size_t n = pixels.size();
    s.beginTile(n);
    s.recordFirstHits = true;
    s.rootViewIndependent.assign(n, Rgb{});
    s.rootLighting.assign(n, Rgb{});
    s.rootLitMask.assign(n, 0);
    {
        StageTimer timer(settings_.stageTimes, s.stages.firstHits);
        s.rays.resize(n);
        s.hits.resize(n);
        for (std::size_t i = 0; i < n; ++i) s.rays[i] = cameraRays.ray(pixels[i].x, pixels[i].y);
        tracer_.intersectPrimary(std::span(s.rays.data(), n), std::span(s.hits.data(), n));
        s.counts.primary += n;
        const RayCone pixel{0.0f, cameraRays.pixelSpread()};
        for (std::size_t i = 0; i < n; ++i) {
            out[i].hit = s.hits[i];
            if (s.hits[i].hit())
                s.vertices.push_back({s.rays[i], s.hits[i], static_cast<int>(i), 1.0f, 1, pixel});
            else
                s.nodes[i].direct = shading_.background(s.rays[i]);
        }
    }
    runWaves(s, cache, FirstWave::Hits, true);
    s.recordFirstHits = false;
    resolveNodes(s, cache, batchKey);
    for (std::size_t i = 0; i < n; ++i) {
        out[i].color = s.nodes[i].color();
        out[i].viewIndependent = s.rootViewIndependent[i];
        out[i].lighting = s.rootLighting[i];
        out[i].litMask = s.rootLitMask[i];
    }
}

void TileKernel::reshadeSurfaces(std::span<const ReshadeRequest> requests, std::uint64_t batchKey, TileScratch& s,
                                 CacheWorker* cache, std::span<Rgb> out) const {
    const std::size_t n = requests.size();
    s.beginTile(n);
    s.reshade = requests;
    for (std::size_t i = 0; i < n; ++i)
        s.vertices.push_back({requests[i].ray, requests[i].hit, static_cast<int>(i), 1.0f, 1});
    runWaves(s, cache, FirstWave::Reshade, false);
    s.reshade = {};
    resolveNodes(s, cache, batchKey);
    for (std::size_t i = 0; i < n; ++i) out[i] = s.nodes[i].color();
}

void TileKernel::renderRays(std::span<const RayTreeRecord> rays, std::span<Rgb> out, TileScratch& s) const {
    const std::size_t n = rays.size();
    s.beginTile(n);
    s.pending.clear();
    for (std::size_t i = 0; i < n; ++i)
        s.pending.push_back({Ray{rays[i].origin, rays[i].direction}, static_cast<int>(i), rays[i].pathWeight,
                             rays[i].depth, TileScratch::Kind::Reflection});
    traceSecondaryRays(s);
    runWaves(s, nullptr, FirstWave::Hits, false);
    resolveNodes(s, nullptr, 0);
    for (std::size_t i = 0; i < n; ++i) out[i] = s.nodes[i].color();
}

void TileKernel::beginWaves(TileScratch& s, CacheWorker* cache) const {
    s.trackTrees = cache && cache_ && cache_->tracksDependencies();
    s.countTreeRays = cache && cache_;
    // Bounds are kept for tracked nodes only, which emitSecondaryRay makes
    // and resets one by one: the camera rays' nodes (most of a tile's) are
    // never tracked, and clearing 168 bytes for each of them took 2.4 % of
    // perf's samples on orbit (`always`, 30 frames).
    if (s.trackTrees && s.nodeBounds.size() < s.nodes.size()) s.nodeBounds.resize(s.nodes.size());
}

void TileKernel::runWaves(TileScratch& s, CacheWorker* cache, FirstWave firstWave, bool coherentShadows) const {
    const bool useCache = cache && cache_;
    if (firstWave != FirstWave::Spawned) {
        beginWaves(s, cache);
        const auto start = Clock::now();
        s.stages.hitsShaded += s.vertices.size();
        if (firstWave != FirstWave::Surfaces) computeSurfaces(s);
        if (firstWave == FirstWave::Reshade) {
            reshadeDirect(s);
        } else {
            traceShadowRays(s, coherentShadows);
            shadeDirect(s);
        }
        s.firstBounce += Clock::now() - start;
        spawnSecondaryRays(s, useCache ? cache : nullptr);
    }
    if (useCache) lookupReuse(s, *cache);
    while (!s.pending.empty()) {
        if (settings_.waveLanes) {
            traceSecondaryRaysInLanes(s);
            shadePackets(s, useCache ? cache : nullptr);
        } else {
            traceSecondaryRays(s);
            s.stages.hitsShaded += s.vertices.size();
            computeSurfaces(s);
            traceShadowRays(s, false);
            shadeDirect(s);
            spawnSecondaryRays(s, useCache ? cache : nullptr);
        }
        if (useCache) lookupReuse(s, *cache);
    }
}

void TileKernel::reshadeDirect(TileScratch& s) const {
    StageTimer timer(settings_.stageTimes, s.stages.directShading);
    std::array<ShadowQuery, kMaxLights> queries;
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
        const TileScratch::PathVertex& v = s.vertices[i];
        const ReshadeRequest& request = s.reshade[static_cast<std::size_t>(v.node)];
        const Material& material = scene_.objects[static_cast<std::size_t>(v.hit.objectId)].material;
        const int count = shading_.shadowQueries(s.surfaces[i], queries.data());
        s.nodes[static_cast<std::size_t>(v.node)].direct =
            request.viewIndependent + shading_.highlights(material, s.surfaces[i], -v.ray.direction,
                                                          std::span(queries.data(), static_cast<std::size_t>(count)),
                                                          request.litMask);
    }
}

namespace {

// Gathers the hits of one wave into sixteen-lane batches of one kind (sphere
// or mesh) and computes each batch's surfaces in one call when it is full.
template <class Lanes>
class SurfaceBatch {
public:
    explicit SurfaceBatch(void (*compute)(const Lanes&, int, SurfacePoint*)) : compute_(compute) {}
    // The lanes, and the lane the next hit goes to; add() then says which
    // vertex of the wave filled it.
    Lanes& lanes() { return lanes_; }
    int next() const { return filled_; }
    void add(std::size_t vertex, std::vector<SurfacePoint>& surfaces) {
        vertex_[static_cast<std::size_t>(filled_)] = vertex;
        if (++filled_ == kFloatLanes) flush(surfaces);
    }
    void flush(std::vector<SurfacePoint>& surfaces) {
        if (filled_ == 0) return;
        compute_(lanes_, filled_, out_.data());
        for (int k = 0; k < filled_; ++k)
            surfaces[vertex_[static_cast<std::size_t>(k)]] = out_[static_cast<std::size_t>(k)];
        filled_ = 0;
    }

private:
    void (*compute_)(const Lanes&, int, SurfacePoint*);
    Lanes lanes_;
    std::array<std::size_t, kFloatLanes> vertex_;
    std::array<SurfacePoint, kFloatLanes> out_;
    int filled_ = 0;
};

template <class Lanes>
void setRay(Lanes& lanes, std::size_t k, const Ray& ray, float t) {
    lanes.originX[k] = ray.origin.x, lanes.originY[k] = ray.origin.y, lanes.originZ[k] = ray.origin.z;
    lanes.directionX[k] = ray.direction.x, lanes.directionY[k] = ray.direction.y;
    lanes.directionZ[k] = ray.direction.z;
    lanes.t[k] = t;
}

}  // namespace

void TileKernel::computeSurfaces(TileScratch& s) const {
    StageTimer timer(settings_.stageTimes, s.stages.surfaces);
    const std::size_t n = s.vertices.size();
    s.surfaces.resize(n);
    s.albedo.resize(n);
    // Sphere and mesh hits in sixteen-lane batches (render/HitLanes.h), each
    // lane surfacePointAt's bits; textured spheres (whose texture
    // coordinates need trigonometry) one by one.
    SurfaceBatch<SphereHitLanes> spheres(sphereSurfaces16);
    SurfaceBatch<MeshHitLanes> meshes(meshSurfaces16);
    // The wave's mesh hits land on triangles scattered over the mesh: ask
    // for all their records first, so that the misses overlap.
    for (std::size_t i = 0; i < n; ++i) {
        const TraceHit& hit = s.vertices[i].hit;
        const SceneObject& object = scene_.objects[static_cast<std::size_t>(hit.objectId)];
        if (const MeshShape* shape = std::get_if<MeshShape>(&object.shape))
            if (const MeshShadingRecords* records = meshShading_.recordsFor(hit.objectId, shape->mesh.get()))
                __builtin_prefetch(&records->triangles[static_cast<std::size_t>(hit.primitiveId)], 0, 2);
    }
    for (std::size_t i = 0; i < n; ++i) {
        const TileScratch::PathVertex& v = s.vertices[i];
        const SceneObject& object = scene_.objects[static_cast<std::size_t>(v.hit.objectId)];
        const Material& material = object.material;
        if (const Sphere* sphere = std::get_if<Sphere>(&object.shape)) {
            if (material.diffuseTexture) {
                s.surfaces[i] = surfacePointAt(object, v.ray, v.hit, true);
                continue;
            }
            SphereHitLanes& lanes = spheres.lanes();
            const auto k = static_cast<std::size_t>(spheres.next());
            setRay(lanes, k, v.ray, v.hit.t);
            lanes.centerX[k] = sphere->center.x, lanes.centerY[k] = sphere->center.y, lanes.centerZ[k] = sphere->center.z;
            lanes.radius[k] = sphere->radius;
            spheres.add(i, s.surfaces);
        } else {
            const auto k = static_cast<std::size_t>(meshes.next());
            setRay(meshes.lanes(), k, v.ray, v.hit.t);
            const TriangleMesh* mesh = std::get<MeshShape>(object.shape).mesh.get();
            setMeshHitLane(meshes.lanes(), k, *mesh, meshShading_.recordsFor(v.hit.objectId, mesh), v.hit.primitiveId,
                           v.hit.u, v.hit.v);
            meshes.add(i, s.surfaces);
        }
    }
    spheres.flush(s.surfaces);
    meshes.flush(s.surfaces);
    // The albedo once every surface (and its texture coordinates) is known.
    for (std::size_t i = 0; i < n; ++i) {
        const Material& material = scene_.objects[static_cast<std::size_t>(s.vertices[i].hit.objectId)].material;
        s.albedo[i] = material.albedo(s.surfaces[i].u, s.surfaces[i].v);
    }
}

void TileKernel::traceShadowRays(TileScratch& s, bool coherent) const {
    StageTimer timer(settings_.stageTimes, s.stages.shadowRays);
    const std::size_t n = s.vertices.size();
    const std::size_t lights = scene_.lights.size();
    s.firstQuery.resize(n + 1);
    s.queries.resize(n * lights);
    std::size_t count = 0;
    // Sixteen surfaces at a time (render/HitLanes.h).
    std::array<int, kFloatLanes + 1> first;
    for (std::size_t base = 0; base < n; base += kFloatLanes) {
        const int lanes = static_cast<int>(std::min<std::size_t>(kFloatLanes, n - base));
        const int written = shading_.shadowQueriesOf16(s.surfaces.data() + base, lanes, s.queries.data() + count,
                                                       first.data());
        for (int k = 0; k < lanes; ++k)
            s.firstQuery[base + static_cast<std::size_t>(k)] = static_cast<int>(count) + first[static_cast<std::size_t>(k)];
        count += static_cast<std::size_t>(written);
    }
    s.firstQuery[n] = static_cast<int>(count);
    s.rays.resize(count);
    s.occluded.resize(count);
    for (std::size_t q = 0; q < count; ++q) s.rays[q] = s.queries[q].ray;
    // Shadow rays of camera hits start close together and head for the same
    // lights: packets, or the light grids. Those of later bounces start
    // farther apart but still head for the same lights: packets too, each
    // light's rays together, in the order their hits were spawned.
    if (coherent) {
        s.shadowLights.resize(count);
        for (std::size_t q = 0; q < count; ++q) s.shadowLights[q] = s.queries[q].lightIndex;
        tracer_.occludedPrimaryShadows(std::span(s.rays.data(), count), std::span(s.shadowLights.data(), count),
                                       std::span(s.occluded.data(), count));
    } else if (lights <= 1) {
        tracer_.occludedCoherent(std::span(s.rays.data(), count), std::span(s.occluded.data(), count));
    } else {
        traceShadowRaysByLight(s, count);
    }
    s.counts.shadow += count;
    if (s.countTreeRays)
        for (std::size_t i = 0; i < n; ++i)
            s.nodes[static_cast<std::size_t>(s.vertices[i].node)].tracedRays +=
                static_cast<std::uint32_t>(s.firstQuery[i + 1] - s.firstQuery[i]);
    if (s.trackTrees)
        for (std::size_t i = 0; i < n; ++i) {
            const auto node = static_cast<std::size_t>(s.vertices[i].node);
            if (!s.nodes[node].tracked) continue;
            // The hit's light depends on every light (even one below its
            // horizon, which may rise) and on what its shadow rays cross,
            // kept apart by their answers (cache/RayTreeBounds.h).
            RayTreeBounds& bounds = s.nodeBounds[node];
            bounds.shaded = true;
            for (int q = s.firstQuery[i]; q < s.firstQuery[i + 1]; ++q)
                bounds.addShadowRay(s.queries[static_cast<std::size_t>(q)].ray.origin,
                                    s.queries[static_cast<std::size_t>(q)].lightIndex,
                                    !s.occluded[static_cast<std::size_t>(q)]);
        }
}

void TileKernel::traceShadowRaysByLight(TileScratch& s, std::size_t count) const {
    // A counting sort by light keeps each light's rays in spawn order.
    const std::size_t lights = scene_.lights.size();
    s.lightStart.assign(lights + 1, 0);
    for (std::size_t q = 0; q < count; ++q) ++s.lightStart[static_cast<std::size_t>(s.queries[q].lightIndex) + 1];
    for (std::size_t l = 0; l < lights; ++l) s.lightStart[l + 1] += s.lightStart[l];
    s.byLight.resize(count);
    s.byLightRays.resize(count);
    s.byLightOccluded.resize(count);
    for (std::size_t q = 0; q < count; ++q) {
        const int slot = s.lightStart[static_cast<std::size_t>(s.queries[q].lightIndex)]++;
        s.byLight[static_cast<std::size_t>(slot)] = static_cast<int>(q);
        s.byLightRays[static_cast<std::size_t>(slot)] = s.rays[q];
    }
    tracer_.occludedCoherent(std::span(s.byLightRays.data(), count), std::span(s.byLightOccluded.data(), count));
    for (std::size_t slot = 0; slot < count; ++slot)
        s.occluded[static_cast<std::size_t>(s.byLight[slot])] = s.byLightOccluded[slot];
}

void TileKernel::shadeDirect(TileScratch& s) const {
    StageTimer timer(settings_.stageTimes, s.stages.directShading);
    // One hit at a time: gathering sixteen hits' records into lanes cost
    // more than the lanes saved (docs/log/2026-11-26-core-lanes.md).
    for (std::size_t i = 0; i < s.vertices.size(); ++i) {
        const TileScratch::PathVertex& v = s.vertices[i];
        const Material& material = scene_.objects[static_cast<std::size_t>(v.hit.objectId)].material;
        const auto first = static_cast<std::size_t>(s.firstQuery[i]);
        const auto count = static_cast<std::size_t>(s.firstQuery[i + 1]) - first;
        s.nodes[static_cast<std::size_t>(v.node)].direct =
            shading_.directLight(material, s.albedo[i], s.surfaces[i], -v.ray.direction,
                                 std::span(s.queries.data() + first, count),
                                 std::span(s.occluded.data() + first, count));
        if (s.recordFirstHits && v.depth == 1)
            s.rootViewIndependent[static_cast<std::size_t>(v.node)] = shading_.viewIndependentLight(
                material, s.albedo[i], s.surfaces[i], std::span(s.queries.data() + first, count),
                std::span(s.occluded.data() + first, count), s.rootLitMask[static_cast<std::size_t>(v.node)]);
        if (s.recordFirstHits && v.depth == 1 && material.diffuseTexture) {
            // Only a texture varies the albedo within a primitive; the
            // lighting of untextured hits is never asked for.
            std::uint64_t sameMask;
            s.rootLighting[static_cast<std::size_t>(v.node)] = shading_.viewIndependentLight(
                material, Rgb{1.0f}, s.surfaces[i], std::span(s.queries.data() + first, count),
                std::span(s.occluded.data() + first, count), sameMask);
        }
    }
}

void TileKernel::emitSecondaryRay(TileScratch& s, CacheWorker* cache, int parent, float parentPathWeight,
                                  int parentDepth, int objectId, const Ray& ray, const RayCone& cone,
                                  TileScratch::Kind kind, float share, bool leavesObject,
                                  const SpawnedRayLookup& lookup) const {
    // Every secondary ray gets a node of its own, whether a cache answers it
    // or not, so caching never changes how the colours are summed.
    const int node = static_cast<int>(s.nodes.size());
    const bool parentTracked = s.nodes[static_cast<std::size_t>(parent)].tracked;
    TileScratch::Node& added = s.nodes.emplace_back();
    if (s.trackTrees) {
        // A fresh record for the node, whether it ends up tracked or not (beginWaves).
        if (s.nodeBounds.size() < s.nodes.size()) s.nodeBounds.resize(s.nodes.size());
        else s.nodeBounds[static_cast<std::size_t>(node)] = RayTreeBounds{};
    }
    added.parent = parent;
    added.weightInParent = share;
    const float pathWeight = parentPathWeight * share;
    // A cube that stands aside this frame (cache/CachePolicy.h), or a ray
    // out of a sampling cube's sample, is not asked: such rays go straight
    // to tracing, as without a cache, and cost no lookup, no miss
    // bookkeeping and no store.
    const bool cached = leavesObject && cache && cache_->cachesObject(objectId);
    if (cached && lookup.answered >= 0) {
        // Looked up already, in lanes: what the lookup batch would have done.
        added.tracked = s.trackTrees;
        if (lookup.answered) {
            added.direct = lookup.color;
            return;
        }
        queueMissedLeavingRay(s, objectId, lookup.texel, {ray, node, pathWeight, parentDepth + 1, kind, cone});
        return;
    }
    if (cached && cache_->admits(objectId, ray.direction, lookup.texel)) {
        s.leaving.push_back({node, pathWeight, parentDepth + 1, kind, cone});
        // Field by field: a whole-struct assignment was built on the stack
        // with narrow stores and copied with wide loads, a store-forwarding
        // stall per query.
        RayCache::Query& q = s.cacheQueries.emplace_back();
        q.objectId = objectId;
        q.origin = ray.origin;
        q.direction = ray.direction;
        q.spread = cone.spread;
        // A cube that sees past its object's surface would answer a ray that
        // meets that surface (a concave mirror seeing itself) with what lies
        // behind it: such a ray is traced.
        q.meetsOwnSurface = cache_->seesPastOwnSurface(objectId) && tracer_.meetsObject(objectId, ray);
        q.texel = lookup.texel;
        added.tracked = s.trackTrees;
    } else {
        if (cached) {
            cache_->countBypassedRay(objectId, *cache);
            // Asked nothing, so traced: what the level record shows for it.
            if (s.recordLevels) noteRootLevel(s, node, pathWeight, CacheLevelImage::kTraced);
        }
        s.pending.push_back({ray, node, pathWeight, parentDepth + 1, kind, cone});
        added.tracked = parentTracked;
    }
}

void TileKernel::spawnSecondaryRays(TileScratch& s, CacheWorker* cache) const {
    StageTimer timer(settings_.stageTimes, s.stages.secondaryRays);
    s.leaving.clear();
    s.cacheQueries.clear();
    s.pending.clear();
    const auto emit = [&](const TileScratch::PathVertex& v, const Ray& ray, const RayCone& cone,
                          TileScratch::Kind kind, float share, bool leavesObject) {
        emitSecondaryRay(s, cache, v.node, v.pathWeight, v.depth, v.hit.objectId, ray, cone, kind, share,
                         leavesObject);
    };
    // One hit at a time: reflected rays computed sixteen at a time, gathered
    // from and scattered back to the wave's records, cost more than this
    // (docs/log/2026-11-26-core-lanes.md).
    const std::size_t n = s.vertices.size();
    for (std::size_t i = 0; i < n; ++i) {
        const TileScratch::PathVertex& v = s.vertices[i];
        if (v.depth >= settings_.maxDepth) continue;
        const Material& material = scene_.objects[static_cast<std::size_t>(v.hit.objectId)].material;
        if (!material.reflects() && !material.refracts()) continue;
        const SurfacePoint& sp = s.surfaces[i];
        const float offset = surfaceOffset(sp.position);
        const RayCone cone = v.cone.bounced(v.hit.t, coneCurvature(scene_.objects[static_cast<std::size_t>(v.hit.objectId)]));
        float reflectWeight = material.reflectivity;
        std::optional<Ray> refracted;
        if (material.refracts()) {
            // Entering: air -> material; leaving: material -> air (objects do not nest).
            const float eta = sp.frontFace ? 1.0f / material.ior : material.ior;
            if (const auto direction = refract(v.ray.direction, sp.normal, eta)) {
                if (v.pathWeight * material.transmissivity >= settings_.minWeight)
                    refracted = Ray{sp.position - sp.geometricNormal * offset, normalize(*direction)};
            } else {
                // Total internal reflection: the transmitted share is reflected.
                reflectWeight += material.transmissivity;
            }
        }
        // The reflected ray's node comes first: nodes are gathered last to
        // first, so the refracted colour is added first, as Whitted's sum has it.
        if (reflectWeight > 0.0f && v.pathWeight * reflectWeight >= settings_.minWeight)
            // Reflection off the outside leaves the object; inside, it stays in.
            emit(v, Ray{sp.position + sp.geometricNormal * offset, normalize(reflect(v.ray.direction, sp.normal))}, cone,
                 TileScratch::Kind::Reflection, reflectWeight, sp.frontFace);
        if (refracted)
            // A refracted ray that exits the object leaves it for the scene;
            // one that enters still has the inside to cross.
            emit(v, *refracted, cone, TileScratch::Kind::Refraction, material.transmissivity, !sp.frontFace);
    }
}

void TileKernel::lookupReuse(TileScratch& s, CacheWorker& cache) const {
    StageTimer timer(settings_.stageTimes, s.stages.reuseLookups);
    const std::size_t n = s.leaving.size();
    if (n == 0) return;
    s.cachedColors.resize(n);
    s.cacheFound.resize(n);
    s.storeTexels.resize(n);
    s.answerTexels.resize(s.trackTrees ? n : 0);
    // Without the cache-level record the batch is looked up exactly as before:
    // an empty span, and one branch here and one after.
    std::span<std::int8_t> answerLevels;
    if (s.recordLevels) {
        s.answerLevels.resize(n);
        answerLevels = s.answerLevels;
    }
    cache_->lookupBatch(s.cacheQueries, s.cachedColors, s.cacheFound, s.storeTexels, cache, s.answerTexels,
                        answerLevels);
    if (s.recordLevels) recordLookupLevels(s);
    for (std::size_t i = 0; i < n; ++i) {
        const TileScratch::LeavingRay& l = s.leaving[i];
        const RayCache::Query& q = s.cacheQueries[i];
        TileScratch::Node& node = s.nodes[static_cast<std::size_t>(l.node)];
        if (s.cacheFound[i]) {
            node.direct = s.cachedColors[i];
            // The answer stands for another tree: whatever it depended on, this
            // one does. Only a tree that is stored asks (the answered node's
            // bounds go nowhere unless its parent's do).
            if (s.trackTrees && s.nodes[static_cast<std::size_t>(node.parent)].tracked)
                cache_->addAnswerDependencies(q.objectId, s.answerTexels[i], s.nodeBounds[static_cast<std::size_t>(l.node)]);
            continue;
        }
        queueMissedLeavingRay(s, q.objectId, s.storeTexels[i],
                              {Ray{q.origin, q.direction}, l.node, l.pathWeight, l.depth, l.kind, l.cone});
    }
}

void TileKernel::queueMissedLeavingRay(TileScratch& s, int objectId, int texel, const TileScratch::PendingRay& ray) {
    s.nodes[static_cast<std::size_t>(ray.node)].store = static_cast<int>(s.stores.size());
    s.stores.push_back({objectId, texel, ray.ray.origin, ray.ray.direction, 0.0f, ray.depth, ray.pathWeight});
    s.pending.push_back(ray);
}

void TileKernel::beginLevelRecord(TileScratch& s, std::size_t roots) {
    s.recordLevels = true;
    s.rootLevels.assign(roots, CacheLevelImage::kNoCachingRay);
    s.rootLevelWeights.assign(roots, 0.0f);
}

void TileKernel::recordLookupLevels(TileScratch& s) {
    for (std::size_t i = 0; i < s.leaving.size(); ++i)
        noteRootLevel(s, s.leaving[i].node, s.leaving[i].pathWeight,
                      s.answerLevels[i] >= 0 ? s.answerLevels[i] : CacheLevelImage::kTraced);
}

void TileKernel::noteRootLevel(TileScratch& s, int node, float pathWeight, std::int8_t level) {
    // The pixel is the root of the ray's tree: a few parents up (at most maxDepth).
    int root = node;
    while (s.nodes[static_cast<std::size_t>(root)].parent >= 0) root = s.nodes[static_cast<std::size_t>(root)].parent;
    const auto r = static_cast<std::size_t>(root);
    // The weightiest lookup stays; on equal weight the one asked first
    // (an earlier wave, or earlier in this batch). See CacheLevelImage.
    if (s.rootLevels[r] != CacheLevelImage::kNoCachingRay && !(pathWeight > s.rootLevelWeights[r])) return;
    s.rootLevels[r] = level;
    s.rootLevelWeights[r] = pathWeight;
}

void TileKernel::composeTile(const TileScratch& s, const TileRange& tile, Image& film) {
    // Row by row: no division per pixel to find its place.
    std::size_t root = 0;
    for (int y = tile.y0; y < tile.y1; ++y)
        for (int x = tile.x0; x < tile.x1; ++x, ++root) film.at(x, y) = s.nodes[root].color();
}

void TileKernel::writeLevelRecord(const TileScratch& s, const TileRange& tile, CacheLevelImage& levels) {
    const int tileWidth = tile.x1 - tile.x0;
    for (std::size_t i = 0; i < s.rootLevels.size(); ++i)
        levels.at(tile.x0 + static_cast<int>(i) % tileWidth, tile.y0 + static_cast<int>(i) / tileWidth) =
            s.rootLevels[i];
}

void TileKernel::traceSecondaryRays(TileScratch& s) const {
    StageTimer timer(settings_.stageTimes, s.stages.traceSecondary);
    const std::size_t n = s.pending.size();
    s.rays.resize(n);
    s.hits.resize(n);
    for (std::size_t i = 0; i < n; ++i) s.rays[i] = s.pending[i].ray;
    // Packets, in the order the rays were spawned: neighbouring pixels'
    // reflections off one mirror stay close, so packets beat single rays
    // even for later bounces (12-20 % less CPU on grid-32, glass and
    // reflective-32; docs/performance.md). Their shadow rays scatter more.
    tracer_.intersectCoherent(std::span(s.rays.data(), n), std::span(s.hits.data(), n));
    s.nextVertices.clear();
    for (std::size_t i = 0; i < n; ++i) {
        const TileScratch::PendingRay& p = s.pending[i];
        const TraceHit& hit = s.hits[i];
        recordTracedRay(s, p, hit.hit(), hit.t);
        if (hit.hit()) s.nextVertices.push_back({p.ray, hit, p.node, p.pathWeight, p.depth, p.cone});
    }
    std::swap(s.vertices, s.nextVertices);
}

void TileKernel::recordTracedRay(TileScratch& s, const TileScratch::PendingRay& ray, bool hit, float t) const {
    if (ray.kind == TileScratch::Kind::Reflection) ++s.counts.reflection;
    else ++s.counts.refraction;
    TileScratch::Node& node = s.nodes[static_cast<std::size_t>(ray.node)];
    ++node.tracedRays;
    if (node.store >= 0) s.stores[static_cast<std::size_t>(node.store)].hitDistance = hit ? t : kKernelInfinity;
    if (node.tracked) {
        RayTreeBounds& bounds = s.nodeBounds[static_cast<std::size_t>(ray.node)];
        if (hit) bounds.addSegment(ray.ray.origin, ray.ray.origin + ray.ray.direction * t);
        else bounds.addEscape(ray.ray.origin, ray.ray.direction);
    }
    if (!hit) node.direct = shading_.background(ray.ray);
}

void TileKernel::resolveNodes(TileScratch& s, CacheWorker* cache, std::uint64_t tileKey) const {
    StageTimer timer(settings_.stageTimes, s.stages.resolve);
    if (cache) cache->beginBatch(tileKey);
    // Nodes are created after their parents, so walking backwards finishes
    // every node's colour before it is stored or passed up.
    for (std::size_t i = s.nodes.size(); i-- > 0;) {
        const TileScratch::Node& node = s.nodes[i];
        if (node.parent < 0) continue;
        const Rgb color = node.color();
        if (node.store >= 0 && cache) {
            const TileScratch::NodeStore& st = s.stores[static_cast<std::size_t>(node.store)];
            std::optional<RayTreeRecord> tree;
            if (s.trackTrees) tree = RayTreeRecord{s.nodeBounds[i], st.origin, st.direction, st.depth, st.pathWeight};
            cache_->store(st.objectId, st.origin, st.direction, color, st.hitDistance, *cache, st.storeTexel,
                          tree ? &*tree : nullptr, node.tracedRays);
        }
        s.nodes[static_cast<std::size_t>(node.parent)].tracedRays += node.tracedRays;
        if (s.nodes[static_cast<std::size_t>(node.parent)].tracked)
            s.nodeBounds[static_cast<std::size_t>(node.parent)].add(s.nodeBounds[i]);
        s.nodes[static_cast<std::size_t>(node.parent)].secondary += color * node.weightInParent;
    }
}

void TileKernel::noteVisiblePoint(TileScratch& s, int root, int objectId, const Vec3& position) const {
    if (!fill_.fills(scene_.objects[static_cast<std::size_t>(objectId)].material)) return;
    s.fillRoots.push_back(root);
    s.fillPositions.push_back(position);
}

void TileKernel::fillFromVisiblePoints(TileScratch& s, CacheWorker* cache, const Vec3& eye) const {
    if (!cache || s.fillRoots.empty()) return;
    StageTimer timer(settings_.stageTimes, s.stages.visibleFill);
    s.visiblePoints.resize(s.fillRoots.size());
    for (std::size_t k = 0; k < s.fillRoots.size(); ++k)
        s.visiblePoints[k] = {s.fillPositions[k], s.nodes[static_cast<std::size_t>(s.fillRoots[k])].color()};
    s.counts.fill += fill_.fillTile(s.visiblePoints, eye, s.fill, *cache);
}

}  // namespace raycache
