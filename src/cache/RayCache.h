#pragma once
// Per-object ray caching (Ruff, Clua and Fernandes 2013): the answer to "what does the ray leaving
// object o at point p in direction s bring back?", when an earlier frame
// already traced it.
//
// How a renderer uses it (see examples/cct_minimal for a whole loop; the
// renderer's own frames go through render/CacheFrame and render/TileKernel):
//
//   RayCache cache(scene, settings);
//   std::vector<CacheWorker> workers = cache.makeWorkers(threadCount);
//   cache.beginFrame(workers);
//   ... in worker w, for each unit of work with a frame-unique key k (a tile):
//       workers[w].beginBatch(k); then for each secondary ray leaving a caching object o:
//         if (auto color = cache.lookup(o, p, s, workers[w])) use *color;
//         else { color = trace(...); cache.store(o, p, s, color, hitDistance, workers[w]); }
//   FrameCacheStats stats = cache.endFrame(workers);
//
// Determinism: lookups during a frame read the caches as they stood when the
// frame began (stores are only queued); endFrame applies the queued stores
// batch by batch in increasing key order, and the first store to an invalid
// texel wins. Images and cache contents therefore do not depend on the
// thread count or scheduling.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cache/CachePolicy.h"
#include "cache/CacheStats.h"
#include "cache/CacheWorker.h"
#include "cache/CdctSearch.h"
#include "cache/CachingCube.h"
#include "cache/CoarseLevels.h"
#include "cache/CubeBudget.h"
#include "cache/RayTreeRecord.h"
#include "cache/ViewSizedResolution.h"
#include "cache/VisibleFill.h"
#include "core/Box3.h"
#include "scene/ObjectBounds.h"
#include "scene/Scene.h"
#include "scene/ScenePose.h"

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
    std::optional<float> cdctToleranceOverride;
    // Which of the improved CDCT's changes are on (benchmark switches: each
    // is measured on its own in docs/performance.md).
    CdctImprovements cdctImprovements;
    // Resolution levels of every CCT cube, the finest included (1..8; 1: a
    // single resolution). Coarser levels fill from the same stores and answer
    // lookups whose pixel footprint is wide enough (cache/CoarseLevels.h,
    // docs/caching.md "Multi-resolution cubes").
    int cubeLevels = 1;
    // A coarser level answers a lookup when its texels span at most this many
    // times the angle between neighbouring pixels' rays leaving the object
    // (Query::spread), and the point its stored ray saw lies within that
    // angle of the looked-up ray. Larger: more answers, further off. In (0, 1000].
    float levelErrorBound = 0.25f;
    // Every CCT cube's face resolution follows the footprints of the rays
    // that look it up (cache/ViewSizedResolution.h, docs/caching.md
    // "Resolution from the view"): the coarsest that keeps them within
    // levelErrorBound, up to its asked resolution (after memoryBudget).
    // CDCT cubes keep their resolution.
    bool resolutionFromView = false;
    // Texels of CCT cubes filled from the surface points the camera's rays
    // shaded, after a visibility ray (render/VisibleSurfaceFill.h). Under
    // invalidationOracle their records are the visibility rays, whose
    // uncached colours they match within rounding (exact fill), not bit for bit.
    VisibleFill visibleFill = VisibleFill::Off;
    // Improved CDCT's pre-fill spread over frames: at most this many texels
    // (rays from a cube's centre) are traced per frame, whole face rows, at
    // least one row; a cube answers lookups once all its rows are in. 0: every
    // cube asked for is filled whole in the frame that first asks for it (a
    // frame that traces a whole 512² cube, 1.5 M rays, per caching object).
    std::int64_t prefillTexelsPerFrame = 0;
    // The most memory the cubes may take (bytes; cache/CubeBudget.h): over
    // it, resolutions are lowered before anything is allocated. None: no limit.
    std::optional<std::size_t> memoryBudget;
    // Benchmark switch: a miss returns black instead of being traced, giving
    // the cost of a frame in which caching objects trace no secondary rays.
    bool ideal = false;
    // Test switch for the invalidation oracle (tests/cache/InvalidationOracleTest):
    // every lookup misses, so each stored colour is its ray's uncached colour,
    // and every valid texel keeps the record of the ray it was traced for
    // (storedTree), so a test can trace it again after the scene changed.
    bool invalidationOracle = false;
    // Animated scenes: a store whose ray tree reached what the last scene
    // change moved (an object's old or new bounds; a changed light, when the
    // tree was shaded) is not made. An animation that moved something this
    // frame most likely moves it again the next, which would drop the texel
    // before any frame reads it: the store, and the drop, would be work for
    // nothing (docs/dynamic-scenes.md, "Stores the next change would drop").
    // Counted in ObjectCacheStats::skippedStores. Likewise an improved-CDCT
    // cube, which any change empties whole, is not pre-filled in a frame that
    // follows a change. Off under invalidationOracle, whose records must
    // cover every texel.
    bool skipStoresReachingChanges = true;
    // Whether a cube steps aside while caching would cost more than it saves
    // (cache/CachePolicy.h, docs/caching.md "Caching that never costs").
    // The library keeps the documents' behaviour unless asked; the CLI's
    // default for cct and cdct is Auto. Always under ideal and
    // invalidationOracle, whose lookups are not the renderer's.
    CachePolicyMode policy = CachePolicyMode::Always;
    // The policy's per-operation costs (calibrated; see CachePolicyCosts).
    CachePolicyCosts policyCosts;
};

class RayCache {
public:
    // Runs body(part) for every part in [0, count), possibly in parallel.
    using PartitionRunner = std::function<void(int count, const std::function<void(int part)>& body)>;
    // The memory budget may lower a cube below CacheSettings::kMinFaceResolution, down to this
    // (a scene of 100 000 caching spheres fits 256 MiB only so).
    static constexpr int kMinBudgetResolution = 4;
    // CDCT: the linear search takes at most ceil(2 * maxDepth / step) steps;
    // parameters asking for more than this are rejected.
    static constexpr double kMaxCdctLinearSteps = 1e6;

    // One cube per object whose (possibly overridden) technique is not None
    // and that reflects or refracts; CDCT cubes get a box bounding the object
    // around its origin. Throws InputError for a resolution outside
    // [CacheSettings::kMinFaceResolution, kMaxFaceResolution] or invalid CDCT parameters.
    RayCache(const Scene& scene, const RayCacheSettings& settings);

    // The technique `object` is cached with under `settings`: None for objects
    // that neither reflect nor refract. The one rule for which objects get a cube.
    static CacheTechnique techniqueFor(const SceneObject& object, const RayCacheSettings& settings);
    // The CDCT search parameters of `object` under `settings`.
    static CdctParameters cdctParametersFor(const SceneObject& object, const RayCacheSettings& settings);
    // Throws InputError unless every parameter is finite and > 0, epsilon <
    // step, the linear search stays within kMaxCdctLinearSteps and the
    // tolerance is at most 1e6 texels. `what` prefixes the message.
    static void validateCdct(const CdctParameters& parameters, const std::string& what);
    // Half-extent per axis of the axis-aligned box centred on the object's
    // origin that bounds its geometry (every component > 0).
    static Vec3 boundingHalfSize(const SceneObject& object);
    // Radius of the sphere centred on the object's origin that holds its geometry.
    static float boundingRadius(const SceneObject& object);

    // Throws the InputError the constructor would throw, without allocating
    // any cube: lets callers reject bad settings before doing any work.
    // Returns what the constructor will allocate: every cube's resolution
    // under settings.memoryBudget, in the order of the cached objects (the
    // cubes not fitting even at kMinBudgetResolution is one of the errors).
    static CubeBudgetPlan validate(const Scene& scene, const RayCacheSettings& settings);
    // RayCacheSettings::visibleFill, Off when no cube is a CCT cube.
    VisibleFill visibleFill() const { return visibleFill_; }
    // What the budget lowered, one line; empty when nothing was.
    const std::string& budgetNote() const { return budgetNote_; }

    bool empty() const { return cubes_.empty(); }
    std::size_t cubeCount() const { return cubes_.size(); }
    bool cachesObject(int objectId) const { return cubeIndexOf(objectId) >= 0; }
    // Whether the object's cube holds what lies past the object's own
    // surface (improved CDCT's pre-fill sees through it) instead of the
    // surface itself: a ray that meets its own object (a concave mirror
    // seeing itself) would be answered with what lies behind, so lookups
    // must mark such rays (Query::meetsOwnSurface).
    bool seesPastOwnSurface(int objectId) const {
        const int c = cubeIndexOf(objectId);
        return c >= 0 && improvements_.traceOwnSurface && fillsByPrefill(cubes_[static_cast<std::size_t>(c)]);
    }
    // The objects for which seesPastOwnSurface holds, ascending.
    std::vector<int> objectsSeenPastThemselves() const;
    // The object's cube; the object must be cached.
    const CachingCube& cube(int objectId) const { return cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))].cube; }
    // The coarser levels of the object's cube (none unless a CCT cube with cubeLevels > 1).
    const CoarseLevels& coarseLevels(int objectId) const {
        return cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))].coarse;
    }
    std::size_t bytes() const;
    // Invalidates every texel of every cube; cubes sized from the view go
    // back to their full resolution.
    void clear();
    // After the scene moved to `posed` (changes from scene/ScenePose.h):
    // every cube of a changed object follows its origin, and the texels
    // whose colour may depend on what changed are invalidated
    // (docs/dynamic-scenes.md, "Which texels a change reaches"):
    //   - CCT cubes, block by block (kBlockSize² texels of one face): a block
    //     goes when the union of its texels' ray-tree bounds may meet the old
    //     or new box of a changed object, or when a light changed and one of
    //     its trees was shaded;
    //   - CDCT cubes as a whole, when anything changed.
    // Returns how many valid texels were dropped. With `runPartitions`, the
    // blocks are tested in parallel.
    std::int64_t sceneChanged(const Scene& posed, const SceneChanges& changes,
                              const PartitionRunner& runPartitions = {});
    // Whether stores carry their tree's record (RayTreeRecord) and texels
    // keep their blocks' bounds: on for animated scenes, where a change must
    // find what it reaches.
    bool tracksDependencies() const { return tracksDependencies_; }
    // Where a change put or took an object: its bounds in one pose.
    struct ChangedRegion {
        PartedBounds bounds;
        int object = -1;
        RegionPose pose = RegionPose::Either;
    };
    // Whether a tree with `bounds` may see a change that reached `regions`
    // (object bounds before and after it) and, if `lightChanged`, the lights:
    // the test that drops a block, and that skips a store. Regions of object
    // `ignoredObject` are left out.
    static bool reaches(const RayTreeBounds& bounds, std::span<const ChangedRegion> regions, bool lightChanged,
                        std::span<const Light> lights, int ignoredObject = -1);
    // Texels per side of the square blocks whose dependencies are kept together.
    static constexpr int kBlockSize = 8;
    // Bytes of the dependency records (included in bytes()).
    std::size_t dependencyBytes() const;
    // What the tree behind a found answer depended on, added to `into`: the
    // bounds of the answering CCT texel's block (`texel`, from lookupBatch's
    // answerTexels), or "everything" for a CDCT answer, whose search read
    // texels of many blocks.
    void addAnswerDependencies(int objectId, int texel, RayTreeBounds& into) const;
    // Texel by texel (bit i of word i / 64), the texels of `objectId`'s cube
    // that the last sceneChanged dropped; empty for a still scene.
    std::span<const std::uint64_t> droppedByLastChange(int objectId) const {
        return cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))].droppedBits;
    }
    // invalidationOracle: the record of the ray that filled texel `texel` of
    // `objectId`'s cube (valid texels only).
    const RayTreeRecord& storedTree(int objectId, int texel) const;

    std::vector<CacheWorker> makeWorkers(int count) const;
    // `count` workers owned by the cache and reused frame after frame, so
    // their store queues keep their memory (render/CacheFrame.h uses them).
    std::span<CacheWorker> reusableWorkers(int count);
    void beginFrame(std::span<CacheWorker> workers);
    // With `runPartitions`, the stores of different cubes are applied by
    // `partitions` calls of its body (each cube's stores in the same order as
    // without), so a caller may spread them over that many threads. Every
    // call scans all queued stores: more partitions than threads add scans,
    // not parallelism.
    FrameCacheStats endFrame(std::span<CacheWorker> workers, const PartitionRunner& runPartitions = {},
                             int partitions = 1);

    // What the ray leaving object `objectId` at `origin` along `direction`
    // brought back in an earlier frame, or nothing if it has to be traced.
    // CCT reads the texel addressed by `direction`; CDCT searches the depths
    // along the ray (docs/caching.md), in a bounded number of steps.
    std::optional<Rgb> lookup(int objectId, const Vec3& origin, const Vec3& direction, CacheWorker& worker) const;

    // A secondary ray leaving a caching object, as a batch lookup sees it.
    struct Query {
        int objectId;
        Vec3 origin;
        Vec3 direction;
        // The spread of the ray's cone (radians): the angle between it and
        // the rays of neighbouring pixels. 0: only the finest level answers.
        float spread = 0.0f;
        // The ray meets its own object (the caller tested it, for the objects
        // of objectsSeenPastThemselves): the cube cannot answer it, so it is
        // a miss, counted as ownSurface.
        bool meetsOwnSurface = false;
        // The CCT texel `direction` addresses, when the caller addressed it
        // already (see laneAddressedFaceSize); -1: the lookup addresses it.
        int texel = -1;
    };
    // lookup() for a batch: found[i] = 1 and colors[i] set when queries[i]
    // is answered, found[i] = 0 otherwise. The same answers and counters as
    // one lookup() per query, except that a CCT cube with coarser levels
    // answers from the finest valid level its query's spread allows
    // (CoarseLevels::coarsestAllowed). CCT's validity bits and texels are
    // prefetched for many queries before any is read, so their memory
    // latencies overlap instead of adding up.
    // For an unanswered CCT query, storeTexels[i] is the texel its store
    // will fill (invalid when the frame began), -1 otherwise; handing it to
    // store() spares addressing the texel twice.
    // `answerTexels` (optional): for an answered query, the finest CCT texel
    // whose dependency block covers the texel that answered it, -1 otherwise
    // (also for a coarse texel wider than a block; see addAnswerDependencies).
    // `answerLevels` (optional): the level that answered each query (0: the
    // finest; CDCT answers are 0, as hitsByLevel counts them), -1 when none
    // did (also in ideal mode, where found is 1 but nothing answered). Asking
    // for them costs one branch per call, none per query.
    void lookupBatch(std::span<const Query> queries, std::span<Rgb> colors, std::span<unsigned char> found,
                     std::span<int> storeTexels, CacheWorker& worker, std::span<int> answerTexels = {},
                     std::span<std::int8_t> answerLevels = {}) const;
    // Whether `objectId`'s lookups this frame may go through lookupAddressed:
    // a CCT cube that caches every texel (not sampling, not standing aside)
    // at one level, with no inherited colours, not resized from the view,
    // no oracle. Its lookups then read a validity bit and a texel, nothing
    // more, and the tile kernel asks them while it spawns the rays.
    bool looksUpInLanes(int objectId) const {
        const int c = cubeIndexOf(objectId);
        if (c < 0 || oracle_) return false;
        const Entry& e = cubes_[static_cast<std::size_t>(c)];
        return e.technique == CacheTechnique::Cct && e.policy.admitsEveryTexel() && e.coarse.levelCount() <= 1 &&
               e.view.fullSize() == 0 && !e.cube.mayInherit();
    }
    // lookupBatch for one ray leaving `objectId` (looksUpInLanes) whose
    // direction addresses `texel`: the same answer and counters. Returns 1
    // with `color` set when answered (in ideal mode a miss is answered
    // black), else 0: the ray is traced and stored at `texel`.
    int lookupAddressed(int objectId, int texel, Rgb& color, CacheWorker& worker) const {
        const auto c = static_cast<std::size_t>(cubeIndexOf(objectId));
        const CachingCube& cube = cubes_[c].cube;
        CacheWorker::Counters& counters = worker.counters_[c];
        ++counters.lookups;
        // cctAnswer's first case: a valid texel, never inherited here.
        if (cube.isValid(texel)) {
            ++counters.hits;
            ++counters.levelHits[0];
            color = cube.readValid(texel);
            return 1;
        }
        ++counters.misses;
        if (ideal_) color = Rgb{};
        return ideal_ ? 1 : 0;
    }
    // What lookupAddressed(objectId, texel) reads, fetched ahead in two
    // steps, as lookupBatch does: the validity bit first, then (once it has
    // arrived) the texel of a valid one. Always inlined: GCC 12 takes a
    // function whose only effect is a prefetch for one without effects, and
    // drops the calls to it.
    [[gnu::always_inline]] void prefetchValidity(int objectId, int texel) const {
        __builtin_prefetch(cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))].cube.validWordOf(texel));
    }
    [[gnu::always_inline]] void prefetchTexelIfValid(int objectId, int texel) const {
        const CachingCube& cube = cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))].cube;
        if (cube.isValid(texel)) __builtin_prefetch(cube.texelWordOf(texel));
    }
    // Improved CDCT (technique Cdct with prefill on): the objects whose cubes
    // were asked for during this frame (by `workers`) and are not filled yet.
    // The renderer fills them after the frame's pixels, before endFrame
    // (render/CachePrefill.h): one ray per texel from the cube's centre through
    // prefillDirection(), answered with completePrefill(). Until then their
    // lookups miss and the rays are traced.
    std::vector<int> objectsAwaitingPrefill(std::span<const CacheWorker> workers) const;
    // Direction from the centre of `objectId`'s cube through the centre of
    // texel `texel` (face-major index, see CachingCube::texels()).
    Vec3 prefillDirection(int objectId, int texel) const;
    // What the ray from the centre along prefillDirection(objectId, i) saw:
    // its color and the distance to its hit (infinity for a miss).
    struct PrefillTexel {
        Rgb color;
        float hitDistance;
        // 1: the ray from the centre met a mirror or glass, whose colour
        // changes with where it is seen from, so a search that meets this
        // texel from elsewhere traces its ray (CdctImprovements::
        // traceViewDependent). A word, not a bool: texels are exchanged as
        // bytes between processes, and a word leaves no padding.
        std::uint32_t viewDependent = 0;
    };
    // Writes every texel of `objectId`'s cube (texels.size() must equal the
    // cube's texel count): color, and depth clamped to maxDepth.
    void completePrefill(int objectId, std::span<const PrefillTexel> texels);

    // The pre-fill spread over frames (RayCacheSettings::prefillTexelsPerFrame):
    // the cubes asked for by `workers` join a queue (in the frame they are
    // first asked for, in cube order); this frame's pieces are the next face
    // rows of the queue, within the budget. Each piece is traced and handed
    // back, in order, with addPrefillRows. With no budget: every queued cube
    // whole, as objectsAwaitingPrefill.
    struct PrefillPiece {
        int objectId;
        int firstRow;  // face-major rows of cube.size() texels, 6·size() in all
        int rows;
    };
    std::vector<PrefillPiece> planPrefill(std::span<const CacheWorker> workers);
    // The traced texels of a planned piece (rows × size() of them); the cube
    // is filled (completePrefill) when its last row is in. Throws
    // std::logic_error for rows out of order.
    void addPrefillRows(int objectId, int firstRow, std::span<const PrefillTexel> texels);

    // Whether `objectId`'s cube stands aside this frame (the cache policy):
    // its lookups miss without looking and its stores are dropped, so its
    // rays are traced exactly as without a cache.
    bool bypassed(int objectId) const {
        const int c = cubeIndexOf(objectId);
        return c >= 0 && cubes_[static_cast<std::size_t>(c)].policy.bypassed();
    }
    // Whether some cube looks rays up this frame (caching or sampling). When
    // none does, a frame is rendered exactly as without a cache
    // (render/CacheFrame.h): no lookups, no stores, no dependency tracking.
    bool anyCubeAsks() const {
        return std::any_of(cubes_.begin(), cubes_.end(), [](const Entry& e) { return !e.policy.bypassed(); });
    }
    // Whether a ray leaving `objectId` along `direction` is looked up this
    // frame: always while its cube caches, never while it stands aside, and
    // while it samples only when the ray's texel is in the sample
    // (cache/CachePolicy.h). The tile kernel traces the others directly.
    // `knownTexel`: the texel `direction` addresses, or -1 if not known yet.
    bool admits(int objectId, const Vec3& direction, int knownTexel = -1) const {
        const Entry& e = cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))];
        // The texel is addressed only for a sampling cube.
        if (!e.policy.sampling()) return !e.policy.bypassed();
        return e.policy.admitsTexel(knownTexel >= 0 ? knownTexel : e.cube.texelIndexFor(direction));
    }
    // The face size of `objectId`'s cube when this frame's lookups of the
    // rays leaving it address CCT texels (a CCT cube that does not stand
    // aside), else 0. A caller that spawns many such rays at once may
    // address them itself (cache/CubeAddressingLanes.h) and hand each
    // texel over in Query::texel and admits().
    int laneAddressedFaceSize(int objectId) const {
        const int c = cubeIndexOf(objectId);
        if (c < 0) return 0;
        const Entry& e = cubes_[static_cast<std::size_t>(c)];
        return e.technique == CacheTechnique::Cct && !e.policy.bypassed() ? e.cube.size() : 0;
    }
    // Counts a ray that left `objectId` while its cube stood aside (or out of
    // its sample), traced without asking the cube (the tile kernel routes such rays around the
    // lookups; ObjectCacheStats::bypassedRays).
    void countBypassedRay(int objectId, CacheWorker& worker) const {
        ++worker.counters_[static_cast<std::size_t>(cubeIndexOf(objectId))].bypassed;
    }

    // Queues what a traced ray brought back (`hitDistance` from origin to its
    // first hit, infinity for a miss) for the end of the frame. CDCT stores
    // it at the texel addressed by centre -> hit point, with that distance
    // (misses and hits beyond maxDepth: the point of the ray at maxDepth).
    // `knownTexel`: the storeTexels answer of lookupBatch for this ray, or -1.
    // `tree`: when tracksDependencies(), what the ray's tree reached; a store
    // without it counts as depending on everything. `tracedRays`: the rays
    // its tree traced (the ray itself, shadow rays, later bounces), for the
    // cache policy's estimate of what a hit spares; 0 when not counted.
    // Nothing is queued for a cube that stands aside (bypassed()), nor for a
    // texel outside the sample of a sampling cube.
    void store(int objectId, const Vec3& origin, const Vec3& direction, const Rgb& color, float hitDistance,
               CacheWorker& worker, int knownTexel = -1, const RayTreeRecord* tree = nullptr,
               std::uint32_t tracedRays = 0) const;

private:
    struct Entry {
        int objectId;
        std::string name;
        CacheTechnique technique;
        CachingCube cube;
        CdctParameters cdct;  // used by CDCT cubes (cube.hasDepth())
        CoarseLevels coarse;  // CCT cubes with cubeLevels > 1
        // CCT cubes under RayCacheSettings::resolutionFromView; fullSize() 0 otherwise.
        ViewSizedResolution view;
        double invalidPercentBefore = 100.0;
        std::uint64_t prefilledTexels = 0;  // written by completePrefill since the last endFrame
        bool prefilled = false;
        bool prefillQueued = false;              // in prefillQueue_
        int prefillRowsDone = 0;                 // rows of a pre-fill spread over frames
        std::vector<PrefillTexel> prefillRows;  // those rows, until the last is in
        float farthestSurface = 0.0f;       // largest stored depth below cdct.maxDepth
        std::optional<DepthPyramid> pyramid;  // built when the cube is pre-filled
        // Improved CDCT, one bit per texel: PrefillTexel::viewDependent.
        std::vector<std::uint64_t> viewDependentBits;
        // tracksDependencies_, CCT cubes: per block, the union of its valid
        // texels' tree bounds (face-major, blocksPerSide² per face).
        std::vector<RayTreeBounds> blocks;
        int blocksPerSide = 0;
        std::vector<RayTreeRecord> storedTrees;  // invalidationOracle: per texel
        std::vector<std::uint64_t> droppedBits;  // tracksDependencies_: see droppedByLastChange
        // Whether the cube caches or stands aside; changed only by endFrame.
        CubePolicy policy;
        // CCT cubes under the `auto` policy: per sampled texel
        // (CubePolicy::sampledTexel), the rays of the tree its colour came
        // from (capped at 255; 0: unknown), so that the hits on sampled
        // texels tell what a hit spares (CubeFrameCounts::recordedHitRays).
        // Written for sampled texels, read only while the cube samples: a
        // record read on every hit made filled caches measurably slower under
        // `auto` than under `always` (docs/log/2026-11-27-cache-policy-sampling.md).
        std::vector<std::uint8_t> treeRays;
        // Block-against-region tests the last scene change made for this
        // cube's texels (CubeFrameCounts::regionTests), until endFrame.
        std::uint64_t regionTests = 0;
    };
    // A sampling cube's region tests times this estimate what full caching's
    // would be, at the sample's share: the sample's share of texels over its
    // share of blocks (1 in 16 runs of 64 texels touch about 2 in 5 blocks).
    // Depends on the face size only: worked out once per size.
    double sampleRegionTestScale(const Entry& e);
    std::vector<std::pair<int, double>> sampleRegionScales_;  // face size, scale
    // Invalidates texel `texel`; if it was valid, marks it dropped. Returns whether it was valid.
    static bool dropTexel(Entry& e, int texel);
    int blockOf(const Entry& e, int texel) const {
        const int n = e.cube.size();
        const int face = texel / (n * n), y = (texel / n) % n, x = texel % n;
        return (face * e.blocksPerSide + y / kBlockSize) * e.blocksPerSide + x / kBlockSize;
    }
    // Invalidates the texels of block `block`; returns how many were valid.
    std::int64_t dropBlock(Entry& e, int block);
    // Empties one cube: texels, pre-fill state, dependency records.
    static void clearEntry(Entry& e);

    static CubeBudgetPlan planBudget(const Scene& scene, const RayCacheSettings& settings);

    // Improved CDCT cube that fills itself by pre-filling (not by stores).
    bool fillsByPrefill(const Entry& e) const {
        return e.technique == CacheTechnique::Cdct && improvements_.prefill;
    }
    // What answers `q` from CCT cube `e`, whose texel `texel` it addresses.
    struct CctAnswer {
        // -1: nothing. 0: the texel itself. k > 0: a texel k levels coarser,
        // in the cube itself (the texel's colour inherited from a coarser
        // resolution) or in its coarser levels.
        int level = -1;
        bool inherited = false;
    };
    // The finest answer whose texel is no wider than q's footprint allows:
    // the texel itself when valid and not inherited, or inherited from a
    // resolution that much coarser; else the finest valid coarser level
    // within the footprint and seeing its point within it (CoarseLevels;
    // counted as rejected when a valid coarse texel failed the point test).
    CctAnswer cctAnswer(const Entry& e, int texel, const Query& q, CacheWorker::Counters& counters) const;
    // endFrame's steps. orderBatches: every worker's batches of stores in
    // key order, into mergeOrder_. mergeStores: applies them, in partitions
    // (see endFrame) through applyStores, counting stores made and skipped
    // into `stats`. recordFrame: the cube's part of the frame's statistics.
    // judgeFrame: its policy's judgement of the frame, and the face size a
    // view-sized cube asks for next (resizedTo), which resizeViewSizedCubes
    // applies. clearQueues: empties a worker's queues for the next frame.
    void orderBatches(std::span<CacheWorker> workers);
    void mergeStores(std::span<CacheWorker> workers, const PartitionRunner& runPartitions, int partitions,
                     FrameCacheStats& stats);
    void applyStores(std::span<CacheWorker> workers, std::size_t part, std::size_t parts, bool skipping,
                     FrameCacheStats& stats);
    static void recordFrame(Entry& e, const CacheWorker::Counters& all, ObjectCacheStats& s);
    void judgeFrame(Entry& e, const CacheWorker::Counters& all, ObjectCacheStats& s);
    void resizeViewSizedCubes(const FrameCacheStats& stats, const PartitionRunner& runPartitions);
    static void clearQueues(CacheWorker& w);
    // Resamples view-sized cube `e` to `size` texels per face side, with its
    // dependency blocks (each new block the union of the old blocks it
    // overlaps) and oracle records; coarser levels start again empty.
    void resizeEntry(Entry& e, int size);
    std::optional<Rgb> answer(const Entry& entry, const Vec3& origin, const Vec3& direction,
                              CacheWorker::Counters& counters) const;
    // lookup() without ideal mode's black for a miss: the cube's answer, counted.
    // A query marked meetsOwnSurface is a miss without a search.
    std::optional<Rgb> lookupAnswer(int objectId, const Vec3& origin, const Vec3& direction, CacheWorker& worker,
                                    bool meetsOwnSurface = false) const;
    // lookupBatch, compiled with and without writing answerLevels so that the
    // batch without pays nothing per query.
    template <bool kRecordLevels>
    void lookupBatchAs(std::span<const Query> queries, std::span<Rgb> colors, std::span<unsigned char> found,
                       std::span<int> storeTexels, CacheWorker& worker, std::span<int> answerTexels,
                       std::span<std::int8_t> answerLevels) const;

    int cubeIndexOf(int objectId) const {
        return objectId >= 0 && static_cast<std::size_t>(objectId) < cubeOfObject_.size()
                   ? cubeOfObject_[static_cast<std::size_t>(objectId)]
                   : -1;
    }

    std::vector<Entry> cubes_;
    std::vector<int> cubeOfObject_;  // object id -> index into cubes_, -1 if uncached
    std::vector<int> prefillQueue_;  // cube indices awaiting a pre-fill spread over frames, oldest first
    // endFrame's batches in merge order; kept to reuse its memory.
    struct BatchRef {
        std::uint64_t key;
        std::size_t worker;
        std::size_t begin, end;
    };
    std::vector<BatchRef> mergeOrder_;
    std::vector<CacheWorker> workerPool_;  // reusableWorkers()
    bool ideal_ = false;
    bool oracle_ = false;
    float levelErrorBound_ = 0.25f;
    bool multiLevel_ = false;  // some cube has coarser levels: stores carry what their ray saw
    int cubeLevels_ = 1;       // RayCacheSettings::cubeLevels
    bool viewSized_ = false;   // RayCacheSettings::resolutionFromView
    VisibleFill visibleFill_ = VisibleFill::Off;
    std::string budgetNote_;
    bool tracksDependencies_ = false;
    CdctImprovements improvements_;
    std::int64_t prefillTexelsPerFrame_ = 0;
    // tracksDependencies_: every object's world boxes in the pose the texels
    // were traced in, and the lights, for sceneChanged.
    std::vector<PartedBounds> objectBounds_;
    // Triangles per part of a mesh's bounds: a moving or deforming mesh is
    // tested part by part once its whole box is reached.
    static constexpr int kTrianglesPerPart = 256;
    // Changed objects' regions are grown by this share of their coordinates
    // (relativeMargin): hit points are computed in float, and ray origins sit a
    // surface offset (render/LocalShading.h, 1e-4 of the coordinates) off their
    // surfaces. Also grows wholeBounds_.
    static constexpr float kRegionGrowth = 1e-3f;
    std::vector<Light> lights_;
    // RayCacheSettings::skipStoresReachingChanges (never under the oracle),
    // and what the sceneChanged before this frame reached (emptied by
    // endFrame: a frame that follows no change skips nothing).
    bool skipStoresReachingChanges_ = false;
    std::vector<ChangedRegion> lastChangeRegions_;
    std::vector<unsigned char> lastChangeTranslated_;   // per object: onlyTranslated in that change
    bool lastChangeLit_ = false;
    // The scene changed before this frame (sceneChanged; endFrame forgets it):
    // with skipStoresReachingChanges_, improved-CDCT cubes, which any change
    // empties, wait for a frame without one to be pre-filled.
    bool changedBeforeThisFrame_ = false;
    // Whether a store into `cachingObject`'s cube with `bounds` reaches the
    // last change (the skip's test).
    bool reachesLastChange(const RayTreeBounds& bounds, int cachingObject) const;
    // Empties the record of the last change (lastChange*). Here, not in a
    // .cpp: sceneChanged and endFrame, in files of their own, both inline it.
    void forgetLastChange() {
        lastChangeRegions_.clear();
        lastChangeTranslated_.clear();
        lastChangeLit_ = false;
    }

    // A caching sphere that moves keeps the texels whose trees are single
    // rays escaping to the environment, as long as those rays, moved along
    // with it, still meet no other object's box: their colour is the
    // environment's in their direction, the same from anywhere
    // (docs/dynamic-scenes.md, "A caching sphere that moves").
    static bool escapesOnly(const RayTreeBounds& bounds);
    // `now` is a sphere whose box (`before` to `after`) kept its size and
    // moved by its origin's step `originStep`.
    static bool onlyTranslated(const SceneObject& now, const Box3& before, const Box3& after, const Vec3& originStep);
    // Whether `bounds`' escaped rays, moved by `movedBy`, meet no box of
    // wholeBounds_ but their own object's.
    bool stillEscapes(const RayTreeBounds& bounds, const Vec3& movedBy, int objectId) const;
    // Every object's box as it stands, grown like the changed regions
    // (tracksDependencies_; empty for scenes of more objects than this, whose
    // moving spheres drop all their texels: a test per block and object).
    std::vector<Box3> wholeBounds_;
    // invalidationOracle: the records of a kept block's texels follow their cube.
    static void shiftBlockRecords(Entry& e, int block, const Vec3& movedBy);
    static constexpr std::size_t kMostObjectsForMovedEscapes = 256;
};

}  // namespace raycache
