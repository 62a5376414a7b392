#pragma once
// The one tile kernel (docs/architecture.md): a wavefront over the rays of one
// tile, in named stages, each run over the whole wave before the next:
//
//   first hits (camera rays as packets, a G-buffer, or rays from a cube's
//   centre) -> surfaces -> shadow rays -> direct shading -> secondary rays ->
//   reuse lookups (one batch) -> misses traced together -> their hits are the
//   next wave ... -> stores queued -> compose
//
// A wave is held as packets of sixteen rays in the tracer's own layout,
// each lane carrying its node, path weight, depth and cone, and every stage
// runs in lanes over them (render/TileKernelWaves.cpp). Every caller's first
// hits become such packets, whoever found them: Embree's packets, the grids
// (their hits put into the lanes), the G-buffer, a batch of camera rays,
// rays from inside an object, reprojected points. Each stage is written once.
//
// Whitted's recursion becomes a loop over bounces. Every ray carries the node
// its colour adds to and its weight there; a node is a pixel (or a pre-fill
// texel), or a ray leaving a caching object that the cache could not answer,
// whose colour is stored in the cache once the tile is done. Max depth,
// minimum weight, total internal reflection and which rays leave an object
// are decided exactly as the recursive form did (render/LocalShading.h for
// the shading itself).
//
// Every pipeline uses it: the ray pipeline (render/FrameRenderer.h), the
// hybrid pipeline (render/DeferredShading.h), the Render Cache's samples
// and reshading (rendercache/), improved CDCT's pre-fill
// (render/CachePrefill.h) and the invalidation oracle's re-trace differ
// only in their first stage.
#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

#include "cache/RayCache.h"
#include "core/Image.h"
#include "core/Parallel.h"
#include "core/RayCounts.h"
#include "raster/GBuffer.h"
#include "render/CacheLevelImage.h"
#include "render/CameraRays.h"
#include "render/FrameStats.h"
#include "render/HitLanes.h"
#include "render/LocalShading.h"
#include "render/MeshShading.h"
#include "render/RayCone.h"
#include "render/RenderCacheSamples.h"
#include "render/RenderSettings.h"
#include "render/SurfacePoint.h"
#include "render/TileCacheBookkeeping.h"
#include "render/TileCacheLevelRecord.h"
#include "render/TileRenderCacheRoots.h"
#include "render/TileTraceBatch.h"
#include "render/TileVisibleFill.h"
#include "render/TileWave.h"
#include "render/VisibleSurfaceFill.h"
#include "trace/TraceScene.h"

namespace raycache {

// Per-worker buffers of the kernel, reused from tile to tile so a frame
// allocates only while its waves grow, one part per feature that uses them.
// Opaque to callers except for what the worker did (counts, times).
class TileScratch {
public:
    RayCounts counts;
    StageTimes stages;  // filled only when RenderSettings::stageTimes is set
    std::chrono::steady_clock::duration firstBounce{}, laterBounces{}, compose{};  // hybrid phases

    // Zeroes the counts and times above; the buffers keep their memory.
    void beginFrame() {
        counts = {};
        stages = {};
        firstBounce = laterBounces = compose = {};
    }

private:
    friend class TileKernel;
    void beginTile(std::size_t roots);

    TileWave wave;                     // every call: the nodes, the wave's packets, the next wave's rays
    TileTraceBatch batch;              // rays traced in one batch call (camera rays, camera hits' shadow rays)
    TileCacheBookkeeping caching;      // with a ray cache: lookups, stores, tree rays and bounds
    TileCacheLevelRecord levelRecord;  // with CacheLevelImage: the level of each pixel's weightiest lookup
    TileRenderCacheRoots renderCache;  // the Render Cache's samples and reshading
    TileVisibleFill visibleFill;       // with the visible-surface fill: the tile's first hits that may fill
};

// What the tile kernel's lanes learned of a spawned ray's cache texel
// (render/TileKernelWaves.cpp), handed to TileKernel::emitSecondaryRay.
struct SpawnedRayLookup {
    int texel = -1;     // the CCT texel its direction addresses; -1: not addressed
    int answered = -1;  // 1: the cache answered `color`; 0: it missed; -1: not asked yet
    Rgb color;
};

class TileKernel {
public:
    // With `cache` (may be null or empty), rays leaving caching objects ask
    // it first and queue what they traced. Throws InputError if the scene
    // has more than kMaxLights lights. Builds the tracer's own-surface tests
    // for the cache's objects (TraceScene::prepareOwnSurfaceTests): make
    // kernels while no ray is in flight.
    TileKernel(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
               const RayCache* cache);

    // Ray pipeline: the tile's camera rays as packets, then the waves; writes
    // the tile's pixels of `film`. `cache` is the worker's view of the cache
    // frame (null: no caching); `tileKey` orders its stores (unique per frame).
    // With `levels` (the film's size; null unless RenderSettings::recordCacheLevels),
    // also the tile's pixels of the cache-level record; the image is the same either way.
    void renderCameraTile(const CameraRays& cameraRays, const TileRange& tile, std::uint64_t tileKey,
                          TileScratch& scratch, CacheWorker* cache, Image& film,
                          CacheLevelImage* levels = nullptr) const;

    // Hybrid pipeline: the first hits come from the G-buffer (surface,
    // albedo); pixels without a surface show the background. `levels` as above.
    void renderGBufferTile(const CameraRays& cameraRays, const GBufferView& gbuffer, const TileRange& tile,
                           std::uint64_t tileKey, TileScratch& scratch, CacheWorker* cache, Image& film,
                           CacheLevelImage* levels = nullptr) const;

    // Improved CDCT's pre-fill: what each ray from inside object `objectId`
    // sees once past the object's own surfaces, shaded as rays at `depth`
    // (weight 1) without asking any cache; out[i] answers rays[i] (colour,
    // and distance to the hit, infinity for a miss). Counted as pre-fill rays.
    void renderFromInside(int objectId, std::span<const Ray> rays, int depth, std::span<RayCache::PrefillTexel> out,
                          TileScratch& scratch) const;

    // Render Cache samples: the camera rays through `pixels` (any set, e.g.
    // scattered over the image), as packets, then the waves; out[i] answers
    // pixels[i]. `batchKey` orders the cache stores, unique per frame.
    void renderCameraPixels(const CameraRays& cameraRays, std::span<const PixelCoord> pixels,
                            std::uint64_t batchKey, TileScratch& scratch, CacheWorker* cache,
                            std::span<PrimarySample> out) const;

    // The colour of each reprojected point seen along its new ray: its kept
    // view-independent light, the highlights of its lit lights from the new
    // eye, and its reflected and refracted rays, which ask the caches first.
    // No shadow rays. out[i] answers requests[i].
    void reshadeSurfaces(std::span<const ReshadeRequest> requests, std::uint64_t batchKey, TileScratch& scratch,
                         CacheWorker* cache, std::span<Rgb> out) const;

    // The colour each ray brings back when traced as a secondary ray at its
    // depth and path weight, asking no cache: what a cached texel would hold
    // if its ray were traced now (the invalidation oracle's re-trace).
    void renderRays(std::span<const RayTreeRecord> rays, std::span<Rgb> out, TileScratch& scratch) const;

    const LocalShading& shading() const { return shading_; }

    // Remakes the per-triangle shading records (render/MeshShading.h) of the
    // meshes that moved since the last call. Call between frames, when no
    // ray is in flight (const for the reason TraceScene::prepareFrame is).
    // A kernel that is not told still renders the same image: it reads a
    // moved mesh's triangles from the mesh, only slower.
    void prepareFrame() const { meshShading_.refresh(scene_); }

private:
    // How a wave's hits learn which lights reach them: shadow rays in
    // packets; the shadow rays of camera rays' hits, which the tracer may
    // answer with its light grids (TraceScene::occludedPrimaryShadows); or
    // not at all, the lights being known (ReshadeRequest::litMask).
    enum class WaveShadows : unsigned char { Traced, OfCameraHits, Known };
    // The cache flags of the tile (tracked trees, counted tree rays), and
    // room for the tracked nodes' bounds: before the first wave is shaded.
    void beginWaves(TileScratch& s, CacheWorker* cache) const;
    // The waves after the first: the lookups of the rays it spawned, the
    // rays left traced as packets and shaded, until no ray is left.
    void runWaves(TileScratch& s, CacheWorker* cache) const;
    // s.wave.packets for a tile's pixels: their camera rays and what each lane
    // carries (root, weight 1, depth 1, the pixel's cone).
    static void startTilePackets(const CameraRays& cameraRays, const TileRange& tile, TileScratch& s);
    // A tile's first wave: its camera rays in s.wave.packets, traced (Embree per
    // packet; the grids over the whole tile, their hits put in the lanes).
    void traceCameraRaysInLanes(const CameraRays& cameraRays, const TileRange& tile, TileScratch& s,
                                CacheWorker* cache) const;
    // The hybrid pipeline's first hits from the G-buffer, as packets whose
    // surfaces are already known (shadePackets with surfacesKnown).
    void readGBufferInLanes(const CameraRays& cameraRays, const GBufferView& gbuffer, const TileRange& tile,
                            TileScratch& s, CacheWorker* cache) const;
    // A first wave from hits found elsewhere (a batch of camera rays, rays
    // from inside an object, reprojected points), packed hit after hit into
    // lanes: beginFirstHits with room for `count`, addFirstHit per hit, endFirstHits.
    static void beginFirstHits(TileScratch& s, std::size_t count);
    static void addFirstHit(TileScratch& s, const Ray& ray, const TraceHit& hit, int node, int depth,
                            const RayCone& cone);
    static void endFirstHits(TileScratch& s);
    // s.wave.pending traced as packets in spawn order: the next wave.
    void traceSecondaryRaysInLanes(TileScratch& s) const;
    // Surfaces (unless `surfacesKnown`: the G-buffer gave them), shadow
    // rays, direct light, then the secondary rays into s.caching.leaving and s.wave.pending.
    void shadePackets(TileScratch& s, CacheWorker* cache, bool surfacesKnown, WaveShadows shadows) const;
    void packetSurfaces(TileWave::HitPacket& packet, MeshHitLanes& meshLanes) const;
    void packetShadowRays(TileScratch& s, std::size_t p) const;
    // The shadow rays of a first wave of camera hits over the whole wave, in
    // one call to the tracer's primary shadow rays (the light grids).
    void cameraHitShadowRays(TileScratch& s) const;
    // What the shadow rays of packet p tell the cache: the rays its nodes'
    // trees traced, and where tracked trees' shadow rays went.
    void recordShadowRays(TileScratch& s, std::size_t p) const;
    void packetDirect(TileScratch& s, std::size_t p) const;
    // The Render Cache's record of camera hits (PrimarySample): the light of
    // packet p's depth-1 lanes split in a view-independent part and
    // highlights (tests/render/ScalarShadingRule.h).
    void recordFirstHitLight(TileScratch& s, std::size_t p) const;
    // Reshading (ReshadeRequest): packet p's kept view-independent light plus
    // its lit lights' highlights from the new eye.
    void reshadePacket(TileScratch& s, std::size_t p) const;
    // A packet's secondary rays in two steps. packetSpawnLanes: the rays in
    // lanes, the texels of those leaving CCT objects, and a prefetch of
    // their validity bits. packetEmit: the lookups, then each ray's node,
    // hit by hit. Where lookups are asked at emission, the first step runs
    // for every packet of the wave, then the texels behind valid bits are
    // prefetched, then the second step, so that the memory arrives meanwhile.
    void packetSpawnLanes(const TileWave::HitPacket& packet, SecondaryRayLanes16& spawned, CacheWorker* cache,
                          bool lookUpInLanes) const;
    void packetEmit(TileScratch& s, const TileWave::HitPacket& packet, SecondaryRayLanes16& spawned,
                    CacheWorker* cache) const;
    // One secondary ray of the hit of node `parent`, of weight `weight` there:
    // its node, then the cache's lookup batch (a ray leaving a caching object
    // whose cube asks) or the rays to trace. Its path weight is the
    // parent's times the weight's largest channel.
    void emitSecondaryRay(TileScratch& s, CacheWorker* cache, int parent, float parentPathWeight, int parentDepth,
                          int objectId, const Ray& ray, const RayCone& cone, TileWave::Kind kind, const Rgb& weight,
                          bool leavesObject, const SpawnedRayLookup& lookup = {}) const;
    void lookupReuse(TileScratch& s, CacheWorker& cache) const;
    // The cache-level record: every root starts with no caching ray; each
    // batch of lookups may replace a root's value (CacheLevelImage says which
    // lookup a pixel keeps); the tile's pixels are written at the end.
    static void beginLevelRecord(TileCacheLevelRecord& record, std::size_t roots);
    // The tile's root colours into the film (roots in row order).
    static void composeTile(const TileWave& wave, const TileRange& tile, Image& film);
    static void recordLookupLevels(TileScratch& s);
    // Records `level` for the pixel at the root of `node`'s tree, unless a
    // weightier (or as weighty and earlier) ray of that pixel was recorded.
    static void noteRootLevel(TileScratch& s, int node, float pathWeight, std::int8_t level);
    static void writeLevelRecord(const TileCacheLevelRecord& record, const TileRange& tile,
                                 CacheLevelImage& levels);
    // What the kernel records of a traced secondary ray: its count, its
    // node's traced rays, a store's hit distance, a tracked tree's segment,
    // and the background where it hit nothing (`hit` false; `t` its distance otherwise).
    void recordTracedRay(TileScratch& s, const TileWave::PendingRay& ray, bool hit, float t) const;
    // A leaving ray its cube did not answer: traced, and what its tree
    // brings back stored at `texel` (-1: the store addresses it) once the tile is done.
    static void queueMissedLeavingRay(TileScratch& s, int objectId, int texel, const TileWave::PendingRay& ray);
    // Adds every node's colour to its parent's, children first, queueing the
    // cache stores of the nodes that stand for traced leaving rays.
    void resolveNodes(TileScratch& s, CacheWorker* cache, std::uint64_t tileKey) const;
    // The visible-surface fill: notes root `root`'s first hit at `position`
    // on `objectId` if it may fill; once the tile is resolved, fills the
    // cubes from the noted points (in the tile's store batch), as seen from `eye`.
    void noteVisiblePoint(TileScratch& s, int root, int objectId, const Vec3& position) const;
    void fillFromVisiblePoints(TileScratch& s, CacheWorker* cache, const Vec3& eye) const;

    const Scene& scene_;
    const TraceScene& tracer_;
    RenderSettings settings_;
    const RayCache* cache_;
    LocalShading shading_;
    VisibleSurfaceFill fill_;
    mutable SceneMeshShading meshShading_;
};

}  // namespace raycache
