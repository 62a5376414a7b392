// RayCache: invalidation. What a scene change drops (sceneChanged and its
// tests), clear(), the dependencies of a found answer, and the invalidation
// oracle's records.
#include "cache/RayCache.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <variant>

#include "core/Errors.h"
#include "scene/ObjectBounds.h"

namespace raycache {

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
        // A cube holding nothing (one standing aside empties itself) has
        // nothing to drop: its blocks (168 bytes each, 6144 at 256² faces)
        // are not read, which light-sweep's eight empty cubes would otherwise cost at every change.
        if (e.cube.validCount() == 0 && e.coarse.validCount() == 0) continue;
        // Deciding reads only; dropping writes validity words that blocks
        // share, so it runs after, on one thread.
        reached.assign(e.blocks.size(), 0);
        const bool cubeTranslated = translated[static_cast<std::size_t>(e.objectId)] != 0;
        const Vec3 movedBy = cubeMovedBy[static_cast<std::size_t>(&e - cubes_.data())];
        // Values of `reached`: 0 kept, 1 dropped, 2 kept with its rays moved along.
        // `tests`: blocks tested times the regions (or boxes) each was tested
        // against, what the cache policy charges the cube for (regionTests).
        constexpr int kChunks = 16;
        std::array<std::uint64_t, kChunks> tests{};
        const auto decide = [&](std::size_t begin, std::size_t end, std::uint64_t& tested) {
            for (std::size_t b = begin; b < end; ++b) {
                const RayTreeBounds& bounds = e.blocks[b];
                if (bounds.empty()) continue;  // no valid texel
                if (cubeTranslated && escapesOnly(bounds)) {
                    tested += std::max<std::size_t>(wholeBounds_.size(), 1);
                    reached[b] = stillEscapes(bounds, movedBy, e.objectId) ? 2 : 1;
                    continue;
                }
                tested += std::max<std::size_t>(changedRegions.size(), 1);
                reached[b] = reaches(bounds, changedRegions, lightChanged, lights_) ? 1 : 0;
            }
        };
        const std::size_t perChunk = (e.blocks.size() + kChunks - 1) / kChunks;
        if (runPartitions)
            runPartitions(kChunks, [&](int chunk) {
                const std::size_t begin = static_cast<std::size_t>(chunk) * perChunk;
                decide(std::min(begin, e.blocks.size()), std::min(begin + perChunk, e.blocks.size()),
                       tests[static_cast<std::size_t>(chunk)]);
            });
        else
            decide(0, e.blocks.size(), tests[0]);
        for (const std::uint64_t t : tests) e.regionTests += t;
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

}  // namespace raycache
