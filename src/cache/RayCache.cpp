#include "cache/RayCache.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "core/Errors.h"
#include "scene/ObjectBounds.h"

namespace raycache {

namespace {

// Changed objects' regions are grown by this share of their coordinates
// (relativeMargin): hit points are computed in float, and ray origins sit a
// surface offset (render/LocalShading.h, 1e-4 of the coordinates) off their
// surfaces.
constexpr float kRegionGrowth = 1e-3f;

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
    if (settings.cdctToleranceOverride) p.tolerance = *settings.cdctToleranceOverride;
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
    positive(p.tolerance, "tolerance");
    if (p.tolerance > 1e6f)
        throw InputError(what + ": cdct tolerance must be at most 1e6 texels (got " + formatNumber(p.tolerance) + ")");
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

float RayCache::boundingRadius(const SceneObject& object) {
    float radius = 0.0f;
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
        radius = length(sphere->center - object.origin) + sphere->radius;
    } else if (const auto* mesh = std::get_if<MeshShape>(&object.shape); mesh && mesh->mesh) {
        for (const Vec3& p : mesh->mesh->positions) radius = std::max(radius, length(p - object.origin));
    }
    return radius;
}

CacheTechnique RayCache::techniqueFor(const SceneObject& object, const RayCacheSettings& settings) {
    const Material& m = object.material;
    if (!m.reflects() && !m.refracts()) return CacheTechnique::None;
    return settings.techniqueOverride.value_or(m.cache.technique);
}

CubeBudgetPlan RayCache::validate(const Scene& scene, const RayCacheSettings& settings) {
    if (settings.resolutionOverride &&
        (*settings.resolutionOverride < kMinResolution || *settings.resolutionOverride > kMaxResolution))
        throw InputError("cache resolution must be between " + std::to_string(kMinResolution) + " and " +
                         std::to_string(kMaxResolution) + " (got " + std::to_string(*settings.resolutionOverride) +
                         ")");
    if (settings.cubeLevels < 1 || settings.cubeLevels > kMaxCubeLevels)
        throw InputError("cache levels must be between 1 and " + std::to_string(kMaxCubeLevels) + " (got " +
                         std::to_string(settings.cubeLevels) + ")");
    if (!(std::isfinite(settings.levelErrorBound) && settings.levelErrorBound > 0.0f &&
          settings.levelErrorBound <= 1000.0f))
        throw InputError("cache level error bound must be a finite number in (0, 1000] (got " +
                         formatNumber(settings.levelErrorBound) + ")");
    if (settings.prefillTexelsPerFrame < 0)
        throw InputError("pre-fill texels per frame must be 0 (whole cubes) or more (got " +
                         std::to_string(settings.prefillTexelsPerFrame) + ")");
    for (const SceneObject& object : scene.objects) {
        const CacheTechnique technique = techniqueFor(object, settings);
        if (technique == CacheTechnique::Cdct || technique == CacheTechnique::CdctParity)
            validateCdct(cdctParametersFor(object, settings), "object '" + object.name + "'");
        const int resolution = settings.resolutionOverride.value_or(object.material.cache.faceResolution);
        if (technique != CacheTechnique::None && (resolution < kMinResolution || resolution > kMaxResolution))
            throw InputError("object '" + object.name + "': cache resolution must be between 16 and 2048");
    }
    return planBudget(scene, settings);
}

CubeBudgetPlan RayCache::planBudget(const Scene& scene, const RayCacheSettings& settings) {
    std::vector<CubeRequest> requests;
    for (const SceneObject& object : scene.objects) {
        const CacheTechnique technique = techniqueFor(object, settings);
        if (technique == CacheTechnique::None) continue;
        requests.push_back({object.name, technique != CacheTechnique::Cct,
                            settings.resolutionOverride.value_or(object.material.cache.faceResolution),
                            std::max(length(boundingHalfSize(object)), 1e-6f),
                            settings.resolutionFromView && technique == CacheTechnique::Cct});
    }
    const bool tracks = !scene.animation.empty() || settings.invalidationOracle;
    return planCubeBudget(requests, settings.memoryBudget, settings.cubeLevels, tracks, kMinBudgetResolution);
}

RayCache::RayCache(const Scene& scene, const RayCacheSettings& settings)
    : ideal_(settings.ideal), oracle_(settings.invalidationOracle), levelErrorBound_(settings.levelErrorBound),
      cubeLevels_(settings.cubeLevels), viewSized_(settings.resolutionFromView),
      tracksDependencies_(!scene.animation.empty() || settings.invalidationOracle),
      improvements_(settings.cdctImprovements), prefillTexelsPerFrame_(settings.prefillTexelsPerFrame),
      skipStoresReachingChanges_(settings.skipStoresReachingChanges && !settings.invalidationOracle) {
    const CubeBudgetPlan plan = validate(scene, settings);
    budgetNote_ = plan.note;
    cubeOfObject_.assign(scene.objects.size(), -1);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        const CacheTechnique technique = techniqueFor(object, settings);
        if (technique == CacheTechnique::None) continue;
        const int resolution = plan.resolutions[cubes_.size()];
        cubeOfObject_[i] = static_cast<int>(cubes_.size());
        if (technique == CacheTechnique::Cct)
            cubes_.push_back(Entry{static_cast<int>(i), object.name, technique, CachingCube(object.origin, resolution)});
        else
            cubes_.push_back(Entry{static_cast<int>(i), object.name, technique,
                                   CachingCube(object.origin, resolution, boundingHalfSize(object)),
                                   cdctParametersFor(object, settings)});
        Entry& e = cubes_.back();
        if (technique == CacheTechnique::Cct && viewSized_) e.view = ViewSizedResolution(resolution);
        if (technique == CacheTechnique::Cct && settings.cubeLevels > 1) {
            e.coarse = CoarseLevels(object.origin, resolution, settings.cubeLevels);
            multiLevel_ = multiLevel_ || e.coarse.levelCount() > 1;
        }
        if (tracksDependencies_ && technique == CacheTechnique::Cct) {
            e.blocksPerSide = (resolution + kBlockSize - 1) / kBlockSize;
            e.blocks.resize(6u * static_cast<std::size_t>(e.blocksPerSide) * static_cast<std::size_t>(e.blocksPerSide));
        }
        if (oracle_) e.storedTrees.resize(e.cube.texelCount());
        if (tracksDependencies_) e.droppedBits.assign((e.cube.texelCount() + 63) / 64, 0);
        const bool mayStepAside = !settings.ideal && !settings.invalidationOracle;
        // A CCT lookup reads the one texel its store would write, so a sample
        // of texels shows what full caching would hit; a CDCT search does not.
        e.policy = CubePolicy(mayStepAside ? settings.policy : CachePolicyMode::Always, settings.policyCosts,
                              technique == CacheTechnique::Cct);
        if (mayStepAside && settings.policy == CachePolicyMode::Auto && technique == CacheTechnique::Cct)
            e.treeRays.assign(e.cube.texelCount(), 0);
    }
    const bool anyCct = std::any_of(cubes_.begin(), cubes_.end(), [](const Entry& e) { return e.technique == CacheTechnique::Cct; });
    if (anyCct) visibleFill_ = settings.visibleFill;
    if (tracksDependencies_) {
        // Only animated objects ever change.
        objectBounds_.resize(scene.objects.size());
        for (const ObjectAnimation& a : scene.animation.objects)
            objectBounds_[static_cast<std::size_t>(a.object)] =
                partedBounds(scene.objects[static_cast<std::size_t>(a.object)], kTrianglesPerPart);
        if (scene.objects.size() <= kMostObjectsForMovedEscapes)
            for (const SceneObject& object : scene.objects) {
                const Box3 box = worldBounds(object);
                wholeBounds_.push_back(box.empty() ? box : PartedBounds{box, {}, {}}.grownRelative(kRegionGrowth).whole);
            }
        lights_ = scene.lights;
    }
}

std::size_t RayCache::bytes() const {
    std::size_t total = dependencyBytes();
    for (const Entry& e : cubes_) total += e.cube.bytes() + e.coarse.bytes();
    return total;
}

std::size_t RayCache::dependencyBytes() const {
    std::size_t total = 0;
    for (const Entry& e : cubes_)
        total += e.blocks.size() * sizeof(RayTreeBounds) + e.storedTrees.size() * sizeof(RayTreeRecord);
    return total;
}

void RayCache::clearEntry(Entry& e) {
    e.cube.clear();
    e.coarse.clear();
    e.prefilled = false;
    // A pre-fill under way starts again: its rows saw the scene before the change.
    e.prefillRowsDone = 0;
    e.prefillRows = {};
    e.farthestSurface = 0.0f;
    e.pyramid.reset();
    e.viewDependentBits.clear();
    std::fill(e.blocks.begin(), e.blocks.end(), RayTreeBounds{});
    std::fill(e.treeRays.begin(), e.treeRays.end(), 0);
}

void RayCache::clear() {
    for (Entry& e : cubes_) {
        clearEntry(e);
        e.policy.restart();
        // A view-sized cube starts again as it was made: at its full resolution, undecided.
        if (e.view.fullSize() > 0) {
            e.view = ViewSizedResolution(e.view.fullSize());
            if (e.cube.size() != e.view.fullSize()) resizeEntry(e, e.view.fullSize());
        }
    }
}

bool RayCache::dropTexel(Entry& e, int texel) {
    if (!e.cube.invalidate(texel)) return false;
    const auto i = static_cast<std::size_t>(texel);
    if (!e.droppedBits.empty()) e.droppedBits[i >> 6] |= std::uint64_t{1} << (i & 63);
    return true;
}

std::int64_t RayCache::dropBlock(Entry& e, int block) {
    const int n = e.cube.size();
    const int perFace = e.blocksPerSide * e.blocksPerSide;
    const int face = block / perFace;
    const int y0 = (block % perFace) / e.blocksPerSide * kBlockSize;
    const int x0 = block % e.blocksPerSide * kBlockSize;
    std::int64_t dropped = 0;
    const int y1 = std::min(y0 + kBlockSize, n), x1 = std::min(x0 + kBlockSize, n);
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) dropped += dropTexel(e, (face * n + y) * n + x) ? 1 : 0;
    // A coarser texel over the block may hold a store of one of its texels.
    dropped += e.coarse.dropOver(face, x0, y0, x1, y1);
    e.blocks[static_cast<std::size_t>(block)] = RayTreeBounds{};
    return dropped;
}

bool RayCache::reaches(const RayTreeBounds& bounds, std::span<const ChangedRegion> regions, bool lightChanged,
                       std::span<const Light> lights, int ignoredObject) {
    if (bounds.dependsOnEverything || (lightChanged && bounds.shaded)) return true;
    // Shadow rays something stopped stay stopped when a ball the change put
    // there stops every one of them, whatever stopped them before (a moving
    // ball's shadow that still covers them). Its radius shrunk by twice the
    // regions' growth (PartedBounds::grownRelative) for rounding.
    bool blockedStayBlocked = false;
    if (bounds.shaded && !bounds.blockedShadowOrigins.empty())
        for (const ChangedRegion& changed : regions) {
            const PartedBounds& region = changed.bounds;
            if (changed.pose != RegionPose::After || !region.isBall() ||
                (ignoredObject >= 0 && changed.object == ignoredObject))
                continue;
            const float growth = relativeMargin(region.whole, kRegionGrowth);
            if (bounds.blockedRaysAllMeetBall(region.ballCentre, region.ballRadius - 2.0f * growth,
                                              region.ballRadius + growth, lights)) {
                blockedStayBlocked = true;
                break;
            }
        }
    for (const ChangedRegion& changed : regions) {
        if (ignoredObject >= 0 && changed.object == ignoredObject) continue;
        const PartedBounds& region = changed.bounds;
        const bool meets = region.isBall()
                               ? bounds.mayMeetBall(region.ballCentre, region.ballRadius, region.whole, lights,
                                                    changed.pose, blockedStayBlocked)
                               : region.any([&](const Box3& box) {
                                     return bounds.mayMeet(box, lights, changed.pose, blockedStayBlocked);
                                 });
        if (meets) return true;
    }
    return false;
}

bool RayCache::escapesOnly(const RayTreeBounds& bounds) {
    return !bounds.escapeOrigins.empty() && bounds.segmentStarts.empty() && !bounds.hasShadowRays() &&
           !bounds.shaded && !bounds.dependsOnEverything;
}

bool RayCache::onlyTranslated(const SceneObject& now, const Box3& before, const Box3& after, const Vec3& originStep) {
    // A sphere whose box kept its size and moved with its origin: every point
    // of its surface moved by the same step, so a ray leaving it moved along.
    if (!std::holds_alternative<Sphere>(now.shape) || before.empty() || after.empty()) return false;
    const Vec3 sizeBefore = before.hi - before.lo, sizeAfter = after.hi - after.lo;
    const Vec3 centreStep = (after.lo + after.hi - before.lo - before.hi) * 0.5f;
    const float scale = std::max({maxComponent(max(-after.lo, after.hi)), maxComponent(max(-before.lo, before.hi)), 1.0f});
    const float slack = 1e-5f * scale;
    for (int a = 0; a < 3; ++a)
        if (std::fabs(sizeBefore[a] - sizeAfter[a]) > slack || std::fabs(centreStep[a] - originStep[a]) > slack)
            return false;
    return true;
}

void RayCache::shiftBlockRecords(Entry& e, int block, const Vec3& movedBy) {
    const int n = e.cube.size();
    const int perFace = e.blocksPerSide * e.blocksPerSide;
    const int face = block / perFace;
    const int y0 = (block % perFace) / e.blocksPerSide * kBlockSize;
    const int x0 = block % e.blocksPerSide * kBlockSize;
    for (int y = y0; y < std::min(y0 + kBlockSize, n); ++y)
        for (int x = x0; x < std::min(x0 + kBlockSize, n); ++x) {
            RayTreeRecord& record = e.storedTrees[static_cast<std::size_t>((face * n + y) * n + x)];
            record.origin += movedBy;
            record.bounds.escapeOrigins = record.bounds.escapeOrigins.shifted(movedBy);
        }
}

bool RayCache::reachesLastChange(const RayTreeBounds& bounds, int cachingObject) const {
    // A caching sphere that only moved keeps the texels whose rays escape
    // (sceneChanged): its own move does not reach them.
    const bool ownMoveKept = static_cast<std::size_t>(cachingObject) < lastChangeTranslated_.size() &&
                             lastChangeTranslated_[static_cast<std::size_t>(cachingObject)] && escapesOnly(bounds);
    return reaches(bounds, lastChangeRegions_, lastChangeLit_, lights_, ownMoveKept ? cachingObject : -1);
}

void RayCache::forgetLastChange() {
    lastChangeRegions_.clear();
    lastChangeTranslated_.clear();
    lastChangeLit_ = false;
}

bool RayCache::stillEscapes(const RayTreeBounds& bounds, const Vec3& movedBy, int objectId) const {
    if (wholeBounds_.empty()) return false;  // more objects than kMostObjectsForMovedEscapes
    const Box3 origins = bounds.escapeOrigins.shifted(movedBy);
    // The rays leave their sphere outward and never meet it again; any other
    // object's box they may meet could now stand in their way.
    for (std::size_t k = 0; k < wholeBounds_.size(); ++k)
        if (static_cast<int>(k) != objectId && boxMeetsRays(wholeBounds_[k], origins, bounds.escapeDirections))
            return false;
    return true;
}

std::int64_t RayCache::sceneChanged(const Scene& posed, const SceneChanges& changes,
                                   const PartitionRunner& runPartitions) {
    forgetLastChange();
    changedBeforeThisFrame_ = !changes.empty();
    if (changes.empty()) return 0;
    const auto changed = [&](int object) {
        return std::binary_search(changes.objects.begin(), changes.objects.end(), object);
    };
    // Per cube, how far its object moved (its cube follows the origin).
    std::vector<Vec3> cubeMovedBy(cubes_.size());
    for (std::size_t c = 0; c < cubes_.size(); ++c) {
        Entry& e = cubes_[c];
        if (!changed(e.objectId)) continue;
        const Vec3 origin = posed.objects[static_cast<std::size_t>(e.objectId)].origin;
        cubeMovedBy[c] = origin - e.cube.center();
        e.cube.moveTo(origin);
        e.coarse.moveTo(origin);
    }
    std::int64_t dropped = 0;
    if (!tracksDependencies_) {
        for (const Entry& e : cubes_) dropped += static_cast<std::int64_t>(e.cube.validCount() + e.coarse.validCount());
        clear();
        return dropped;
    }
    // Where the changed objects were and are, whole and by parts. Grown a
    // little: hit points are computed in float, and ray origins sit a surface
    // offset (render/LocalShading.h, 1e-4 of the coordinates) off their surfaces.
    std::vector<ChangedRegion> changedRegions;
    // Where the changed objects will be if they go on as they went: now,
    // moved once more by what this change moved them (the stores skipped
    // until the next change are those reaching it; a guess, never a drop).
    std::vector<ChangedRegion> nextRegions;
    // Per object: a caching sphere that only moved, by its cube's step (onlyTranslated).
    std::vector<unsigned char> translated(posed.objects.size(), 0);
    for (const int object : changes.objects) {
        const auto i = static_cast<std::size_t>(object);
        PartedBounds now = partedBounds(posed.objects[i], kTrianglesPerPart);
        const int c = cubeIndexOf(object);
        if (c >= 0)
            translated[i] = onlyTranslated(posed.objects[i], objectBounds_[i].whole, now.whole,
                                           cubeMovedBy[static_cast<std::size_t>(c)]);
        if (!wholeBounds_.empty()) wholeBounds_[i] = now.whole.empty() ? Box3{} : now.grownRelative(kRegionGrowth).whole;
        if (!objectBounds_[i].whole.empty())
            changedRegions.push_back({objectBounds_[i].grownRelative(kRegionGrowth), object, RegionPose::Before});
        if (!now.whole.empty()) changedRegions.push_back({now.grownRelative(kRegionGrowth), object, RegionPose::After});
        if (skipStoresReachingChanges_ && !now.whole.empty() && !objectBounds_[i].whole.empty()) {
            const Box3& before = objectBounds_[i].whole;
            const Vec3 moved = (now.whole.lo + now.whole.hi - before.lo - before.hi) * 0.5f;
            nextRegions.push_back({PartedBounds{now.whole, {}, {}}.shifted(moved).grownRelative(kRegionGrowth), object,
                                   RegionPose::Either});
        }
        objectBounds_[i] = std::move(now);
    }
    lights_ = posed.lights;
    const bool lightChanged = !changes.lights.empty();
    std::vector<unsigned char> reached;
    for (Entry& e : cubes_) {
        std::fill(e.droppedBits.begin(), e.droppedBits.end(), 0);
        if (e.blocks.empty()) {  // CDCT: its searches read across blocks; all or nothing
            // A cube that holds nothing and fills nothing (one that waits for
            // the scene to stop) has nothing to drop: skip walking its texels.
            if (e.cube.validCount() == 0 && !e.prefilled && e.prefillRowsDone == 0) continue;
            for (int t = 0; t < static_cast<int>(e.cube.texelCount()); ++t) dropped += dropTexel(e, t) ? 1 : 0;
            clearEntry(e);
            continue;
        }
        // Deciding reads only; dropping writes validity words that blocks
        // share, so it runs after, on one thread.
        reached.assign(e.blocks.size(), 0);
        const bool cubeTranslated = translated[static_cast<std::size_t>(e.objectId)] != 0;
        const Vec3 movedBy = cubeMovedBy[static_cast<std::size_t>(&e - cubes_.data())];
        // Values of `reached`: 0 kept, 1 dropped, 2 kept with its rays moved along.
        const auto decide = [&](std::size_t begin, std::size_t end) {
            for (std::size_t b = begin; b < end; ++b) {
                const RayTreeBounds& bounds = e.blocks[b];
                if (bounds.empty()) continue;  // no valid texel
                if (cubeTranslated && escapesOnly(bounds)) {
                    reached[b] = stillEscapes(bounds, movedBy, e.objectId) ? 2 : 1;
                    continue;
                }
                reached[b] = reaches(bounds, changedRegions, lightChanged, lights_) ? 1 : 0;
            }
        };
        constexpr int kChunks = 16;
        const std::size_t perChunk = (e.blocks.size() + kChunks - 1) / kChunks;
        if (runPartitions)
            runPartitions(kChunks, [&](int chunk) {
                const std::size_t begin = static_cast<std::size_t>(chunk) * perChunk;
                decide(std::min(begin, e.blocks.size()), std::min(begin + perChunk, e.blocks.size()));
            });
        else
            decide(0, e.blocks.size());
        for (std::size_t b = 0; b < e.blocks.size(); ++b) {
            if (reached[b] == 1) dropped += dropBlock(e, static_cast<int>(b));
            if (reached[b] == 2) {
                e.blocks[b].escapeOrigins = e.blocks[b].escapeOrigins.shifted(movedBy);
                if (oracle_) shiftBlockRecords(e, static_cast<int>(b), movedBy);
            }
        }
    }
    if (skipStoresReachingChanges_) {
        // Whole boxes only: a store is tested where a block is, and skipping
        // one too many only costs a trace.
        // Either pose: the next change's old pose is this one's new.
        lastChangeRegions_.clear();
        for (const ChangedRegion& region : changedRegions)
            lastChangeRegions_.push_back({PartedBounds{region.bounds.whole, {}, {}}, region.object, RegionPose::Either});
        for (ChangedRegion& region : nextRegions) lastChangeRegions_.push_back(std::move(region));
        lastChangeTranslated_ = std::move(translated);
        lastChangeLit_ = lightChanged;
    }
    return dropped;
}

void RayCache::addAnswerDependencies(int objectId, int texel, RayTreeBounds& into) const {
    const Entry& e = cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))];
    if (e.blocks.empty() || texel < 0) {
        into.dependsOnEverything = true;
        return;
    }
    into.add(e.blocks[static_cast<std::size_t>(blockOf(e, texel))]);
}

const RayTreeRecord& RayCache::storedTree(int objectId, int texel) const {
    const Entry& e = cubes_[static_cast<std::size_t>(cubeIndexOf(objectId))];
    if (!oracle_ || !e.cube.isValid(texel))
        throw RuntimeError("storedTree: texel " + std::to_string(texel) + " of '" + e.name +
                           "' keeps no record (invalidation oracle off, or texel invalid)");
    return e.storedTrees[static_cast<std::size_t>(texel)];
}

std::vector<CacheWorker> RayCache::makeWorkers(int count) const {
    std::vector<CacheWorker> workers(static_cast<std::size_t>(count));
    for (CacheWorker& w : workers) w.counters_.resize(cubes_.size());
    return workers;
}

std::span<CacheWorker> RayCache::reusableWorkers(int count) {
    const auto n = static_cast<std::size_t>(count);
    if (workerPool_.size() < n) workerPool_.resize(n);
    for (CacheWorker& w : workerPool_) w.counters_.resize(cubes_.size());
    return std::span(workerPool_).first(n);
}

void RayCache::beginFrame(std::span<CacheWorker> workers) {
    for (Entry& e : cubes_)
        e.invalidPercentBefore =
            100.0 * static_cast<double>(e.cube.texelCount() - e.cube.validCount()) / static_cast<double>(e.cube.texelCount());
    for (CacheWorker& w : workers) {
        w.pending_.clear();
        w.pendingTrees_.clear();
        w.pendingSeen_.clear();
        w.batches_.clear();
        w.counters_.assign(cubes_.size(), CacheWorker::Counters{});
    }
}

FrameCacheStats RayCache::endFrame(std::span<CacheWorker> workers, const PartitionRunner& runPartitions,
                                   int partitions) {
    // Batches in key order; only their boundaries are sorted (one per tile),
    // never the stores themselves.
    mergeOrder_.clear();
    for (std::size_t w = 0; w < workers.size(); ++w) {
        workers[w].closeBatch();
        for (const CacheWorker::Batch& b : workers[w].batches_)
            if (b.end > b.begin) mergeOrder_.push_back({b.key, w, b.begin, b.end});
    }
    std::sort(mergeOrder_.begin(), mergeOrder_.end(), [](const BatchRef& a, const BatchRef& b) {
        return a.key != b.key ? a.key < b.key : a.worker < b.worker;
    });

    FrameCacheStats stats;
    stats.objects.resize(cubes_.size());
    const bool skipping = skipStoresReachingChanges_ && (!lastChangeRegions_.empty() || lastChangeLit_);
    // Partition `part` of `parts` applies the stores of cubes c with
    // c % parts == part: cubes are independent, so partitions may run in
    // parallel, and each cube still sees its stores in merge order. Stores
    // land on scattered texels of large cubes: those a little ahead are
    // prefetched so the memory misses overlap.
    const auto applyPartition = [&](std::size_t part, std::size_t parts) {
        // Far enough ahead that several of this partition's own stores are
        // in flight (a partition owns about 1/parts of them).
        constexpr std::size_t kAhead = 48;
        for (const BatchRef& b : mergeOrder_) {
            const auto& pending = workers[b.worker].pending_;
            for (std::size_t i = b.begin; i < b.end; ++i) {
                if (i + kAhead < b.end) {
                    const auto& ahead = pending[i + kAhead];
                    if (ahead.cube % parts == part) {
                        __builtin_prefetch(cubes_[ahead.cube].cube.validWordOf(ahead.texel), 1);
                        __builtin_prefetch(cubes_[ahead.cube].cube.texelWordOf(ahead.texel), 1);
                    }
                }
                const auto& p = pending[i];
                if (p.cube % parts != part) continue;
                Entry& e = cubes_[p.cube];
                if (skipping && reachesLastChange(workers[b.worker].pendingTrees_[i].bounds, e.objectId)) {
                    ++stats.objects[p.cube].skippedStores;
                    continue;
                }
                const bool finest = e.cube.writeIfInvalid(p.texel, p.packed, p.depth);
                const bool coarser =
                    e.coarse.levelCount() > 1 && e.coarse.writeOver(p.texel, p.packed, workers[b.worker].pendingSeen_[i]) > 0;
                if (!finest && !coarser) continue;
                if (finest) {
                    ++stats.objects[p.cube].stores;
                    if (!e.treeRays.empty() && CubePolicy::sampledTexel(p.texel))
                        e.treeRays[static_cast<std::size_t>(p.texel)] =
                            static_cast<std::uint8_t>(std::min<std::uint32_t>(p.treeRays, 255));
                }
                if (tracksDependencies_) {
                    // The block covers the coarser texels written too (their
                    // answers take its bounds, see addAnswerDependencies).
                    const RayTreeRecord& tree = workers[b.worker].pendingTrees_[i];
                    if (!e.blocks.empty()) e.blocks[static_cast<std::size_t>(blockOf(e, p.texel))].add(tree.bounds);
                    if (oracle_ && finest) e.storedTrees[static_cast<std::size_t>(p.texel)] = tree;
                }
                if (p.depth < e.cdct.maxDepth) e.farthestSurface = std::max(e.farthestSurface, p.depth);
            }
        }
    };
    // One partition per thread: each scans all queued stores once (a 1024²
    // grid-32 CCT frame merged 15-20 % faster on 2 threads with 2 partitions
    // than with 4, and 30 % faster on 1 thread with 1: docs/cluster.md).
    const int parts = runPartitions ? std::clamp(partitions, 1, std::max(1, static_cast<int>(cubes_.size()))) : 1;
    // A frame with nothing to merge (every cube standing aside) starts no
    // parallel work.
    if (!mergeOrder_.empty()) {
        if (parts > 1)
            runPartitions(parts, [&](int part) {
                applyPartition(static_cast<std::size_t>(part), static_cast<std::size_t>(parts));
            });
        else
            applyPartition(0, 1);
    }
    // The change is this frame's: a frame rendered without one stores everything.
    changedBeforeThisFrame_ = false;
    forgetLastChange();

    for (std::size_t c = 0; c < cubes_.size(); ++c) {
        ObjectCacheStats& s = stats.objects[c];
        s.objectId = cubes_[c].objectId;
        s.name = cubes_[c].name;
        s.resolution = cubes_[c].cube.size();
        s.levels = cubes_[c].coarse.levelCount();
        // All levels, with the dependency records of an animated scene's cube.
        s.bytes = cubes_[c].cube.bytes() + cubes_[c].coarse.bytes() + cubes_[c].blocks.size() * sizeof(RayTreeBounds);
        s.invalidPercentBefore = cubes_[c].invalidPercentBefore;
        s.prefilledTexels = cubes_[c].prefilledTexels;
        cubes_[c].prefilledTexels = 0;
        CacheWorker::Counters all;
        for (const CacheWorker& w : workers) all += w.counters_[c];
        s.lookups = all.lookups;
        s.hits = all.hits;
        s.misses = all.misses;
        s.rejected = all.rejected;
        s.ownSurface = all.ownSurface;
        s.viewDependent = all.viewDependent;
        s.hitsByLevel = all.levelHits;
        // Colours inherited from a coarser resolution answer at their level too.
        for (int k = s.levels; k < kMaxCubeLevels; ++k)
            if (all.levelHits[static_cast<std::size_t>(k)] > 0) s.levels = k + 1;
        s.cdctSearches = all.cdctSearches;
        s.cdctSteps = all.cdctSteps;
        s.cdctStepsHistogram = all.cdctStepsHistogram;
        Entry& e = cubes_[c];
        // The policy judges the frame from counts summed over every worker
        // (and, in a cluster job, every process): the same decision everywhere.
        s.state = e.policy.state();
        s.bypassedRays = all.bypassed;
        s.queuedStores = all.queuedStores;
        const CubePolicy::Judgement judged =
            e.policy.afterFrame({all.lookups, all.hits, all.queuedStores, all.tracedTrees, all.treeRays, all.cdctSteps,
                                 all.recordedHits, all.recordedHitRays});
        s.policySaving = judged.saving;
        s.policyCost = judged.cost;
        s.next = e.policy.state();
        s.framesCaching = e.policy.framesCaching();
        s.framesSampling = e.policy.framesSampling();
        s.framesBypassed = e.policy.framesBypassed();
        s.meanTree = e.policy.meanTree();
        if (e.view.fullSize() > 0) {
            const int size = e.view.fullSize() >> e.view.afterFrame(all.lookupsByAllowedLevel);
            if (size != e.cube.size()) s.resizedTo = size;
        }
    }
    // Cubes are resampled independently of each other, so in parallel.
    std::vector<std::size_t> resized;
    for (std::size_t c = 0; c < cubes_.size(); ++c)
        if (stats.objects[c].resizedTo > 0) resized.push_back(c);
    const auto resize = [&](int i) {
        const std::size_t c = resized[static_cast<std::size_t>(i)];
        resizeEntry(cubes_[c], stats.objects[c].resizedTo);
    };
    if (runPartitions && resized.size() > 1) runPartitions(static_cast<int>(resized.size()), resize);
    else
        for (std::size_t i = 0; i < resized.size(); ++i) resize(static_cast<int>(i));
    for (CacheWorker& w : workers) {
        w.pending_.clear();
        w.pendingTrees_.clear();
        w.pendingSeen_.clear();
        w.batches_.clear();
    }
    return stats;
}

void RayCache::resizeEntry(Entry& e, int size) {
    const int from = e.cube.size();
    std::vector<int> sourceOf;
    CachingCube resized = e.cube.resampled(size, oracle_ ? &sourceOf : nullptr);
    if (oracle_) {
        std::vector<RayTreeRecord> trees(resized.texelCount());
        for (std::size_t t = 0; t < trees.size(); ++t)
            if (sourceOf[t] >= 0) trees[t] = e.storedTrees[static_cast<std::size_t>(sourceOf[t])];
        e.storedTrees = std::move(trees);
    }
    if (!e.blocks.empty()) {
        // Each new block takes the union of the old blocks its texels lie in
        // (finer) or cover (coarser): what its texels' colours came from.
        const int perSide = (size + kBlockSize - 1) / kBlockSize;
        std::vector<RayTreeBounds> blocks(6u * static_cast<std::size_t>(perSide) * static_cast<std::size_t>(perSide));
        const auto oldRange = [&](int first, int last) {  // new texels [first, last] -> old blocks
            if (size > from) return std::pair{first / (size / from) / kBlockSize, last / (size / from) / kBlockSize};
            return std::pair{first * (from / size) / kBlockSize, ((last + 1) * (from / size) - 1) / kBlockSize};
        };
        for (int face = 0; face < 6; ++face)
            for (int by = 0; by < perSide; ++by)
                for (int bx = 0; bx < perSide; ++bx) {
                    const auto [ox0, ox1] = oldRange(bx * kBlockSize, std::min(bx * kBlockSize + kBlockSize, size) - 1);
                    const auto [oy0, oy1] = oldRange(by * kBlockSize, std::min(by * kBlockSize + kBlockSize, size) - 1);
                    RayTreeBounds& into = blocks[static_cast<std::size_t>((face * perSide + by) * perSide + bx)];
                    for (int oy = oy0; oy <= oy1; ++oy)
                        for (int ox = ox0; ox <= ox1; ++ox)
                            into.add(e.blocks[static_cast<std::size_t>((face * e.blocksPerSide + oy) * e.blocksPerSide + ox)]);
                }
        e.blocks = std::move(blocks);
        e.blocksPerSide = perSide;
    }
    if (!e.droppedBits.empty()) e.droppedBits.assign((resized.texelCount() + 63) / 64, 0);
    // Resampled colours are inherited, not stored by a tree of their own.
    if (!e.treeRays.empty()) e.treeRays.assign(resized.texelCount(), 0);
    if (e.coarse.levelCount() > 1) e.coarse = CoarseLevels(resized.center(), size, cubeLevels_);
    e.cube = std::move(resized);
}

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

std::vector<int> RayCache::objectsSeenPastThemselves() const {
    std::vector<int> objects;
    for (const Entry& e : cubes_)
        if (improvements_.traceOwnSurface && fillsByPrefill(e)) objects.push_back(e.objectId);
    std::sort(objects.begin(), objects.end());
    return objects;
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

void RayCache::store(int objectId, const Vec3& origin, const Vec3& direction, const Rgb& color, float hitDistance,
                     CacheWorker& worker, int knownTexel, const RayTreeRecord* tree, std::uint32_t tracedRays) const {
    const auto c = static_cast<std::size_t>(cubeIndexOf(objectId));
    if (cubes_[c].policy.bypassed()) return;
    CacheWorker::Counters& counters = worker.counters_[c];
    ++counters.queuedStores;
    if (tracedRays > 0) {
        ++counters.tracedTrees;
        counters.treeRays += tracedRays;
    }
    const auto queueTree = [&] {
        if (!tracksDependencies_) return;
        if (tree) {
            worker.pendingTrees_.push_back(*tree);
        } else {
            RayTreeRecord unknown;
            unknown.bounds.dependsOnEverything = true;
            worker.pendingTrees_.push_back(unknown);
        }
    };
    // What the ray saw, for the coarser levels' error check.
    SeenPoint seen;
    if (cubes_[c].coarse.levelCount() > 1) {
        const Vec3 d = normalize(direction);
        seen = std::isfinite(hitDistance) ? SeenPoint{origin + d * hitDistance, 1.0f} : SeenPoint{d, 0.0f};
    }
    const auto queueSeen = [&] {
        if (multiLevel_) worker.pendingSeen_.push_back(seen);
    };
    if (knownTexel >= 0) {
        if (!cubes_[c].policy.admitsTexel(knownTexel)) return;
        worker.queue({static_cast<std::uint32_t>(c), knownTexel, CachingCube::encodeTexel(color), CachingCube::kInvalidDepth,
                      tracedRays});
        queueSeen();
        queueTree();
        return;
    }
    if (fillsByPrefill(cubes_[c])) return;  // its pre-fill writes every texel
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
            toHit = origin + d * rayParameterAtDistance(cube.center(), origin, d, maxDepth) - cube.center();
            depth = maxDepth;
        }
        if (!isFinite(toHit)) return;
        texel = cube.texelIndexFor(toHit);
    } else {
        texel = cube.texelIndexFor(direction);
    }
    // Lookups read the frame-start state, so only texels invalid then are worth queuing.
    if (cube.isValid(texel) || !cubes_[c].policy.admitsTexel(texel)) return;
    worker.queue({static_cast<std::uint32_t>(c), texel, CachingCube::encodeTexel(color), depth, tracedRays});
    queueSeen();
    queueTree();
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
