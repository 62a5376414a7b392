// RayCache: the frame's stores. Workers queue them (store) while the frame
// is traced; endFrame merges them in key order (skipping those that reach
// the last change), sums the counters, lets each cube's policy judge the
// frame and resizes view-sized cubes.
#include "cache/RayCache.h"

#include <algorithm>
#include <cmath>

namespace raycache {

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
        clearQueues(w);
        w.counters_.assign(cubes_.size(), CacheWorker::Counters{});
    }
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

bool RayCache::reachesLastChange(const RayTreeBounds& bounds, int cachingObject) const {
    // A caching sphere that only moved keeps the texels whose rays escape
    // (sceneChanged): its own move does not reach them.
    const bool ownMoveKept = static_cast<std::size_t>(cachingObject) < lastChangeTranslated_.size() &&
                             lastChangeTranslated_[static_cast<std::size_t>(cachingObject)] && escapesOnly(bounds);
    return reaches(bounds, lastChangeRegions_, lastChangeLit_, lights_, ownMoveKept ? cachingObject : -1);
}

FrameCacheStats RayCache::endFrame(std::span<CacheWorker> workers, const PartitionRunner& runPartitions,
                                   int partitions) {
    orderBatches(workers);
    FrameCacheStats stats;
    stats.objects.resize(cubes_.size());
    mergeStores(workers, runPartitions, partitions, stats);
    // The change is this frame's: a frame rendered without one stores everything.
    changedBeforeThisFrame_ = false;
    forgetLastChange();
    for (std::size_t c = 0; c < cubes_.size(); ++c) {
        CacheWorker::Counters all;
        for (const CacheWorker& w : workers) all += w.counters_[c];
        ObjectCacheStats& s = stats.objects[c];
        recordFrame(cubes_[c], all, s);
        judgeFrame(cubes_[c], all, s);
    }
    resizeViewSizedCubes(stats, runPartitions);
    for (CacheWorker& w : workers) clearQueues(w);
    return stats;
}

void RayCache::clearQueues(CacheWorker& w) {
    w.pending_.clear();
    w.pendingTrees_.clear();
    w.pendingSeen_.clear();
    w.batches_.clear();
}

void RayCache::orderBatches(std::span<CacheWorker> workers) {
    // Only the batches' boundaries are sorted (one per tile), never the stores themselves.
    mergeOrder_.clear();
    for (std::size_t w = 0; w < workers.size(); ++w) {
        workers[w].closeBatch();
        for (const CacheWorker::Batch& b : workers[w].batches_)
            if (b.end > b.begin) mergeOrder_.push_back({b.key, w, b.begin, b.end});
    }
    std::sort(mergeOrder_.begin(), mergeOrder_.end(), [](const BatchRef& a, const BatchRef& b) {
        return a.key != b.key ? a.key < b.key : a.worker < b.worker;
    });
}

void RayCache::mergeStores(std::span<CacheWorker> workers, const PartitionRunner& runPartitions, int partitions,
                           FrameCacheStats& stats) {
    const bool skipping = skipStoresReachingChanges_ && (!lastChangeRegions_.empty() || lastChangeLit_);
    // One partition per thread: each scans all queued stores once, so more
    // partitions than threads only repeat the scan (measured in
    // docs/log/2026-11-28-moved-from-reference-pages.md, from cluster.md).
    const int parts = runPartitions ? std::clamp(partitions, 1, std::max(1, static_cast<int>(cubes_.size()))) : 1;
    // A frame with nothing to merge (every cube standing aside) starts no
    // parallel work.
    if (mergeOrder_.empty()) return;
    if (parts > 1)
        runPartitions(parts, [&](int part) {
            applyStores(workers, static_cast<std::size_t>(part), static_cast<std::size_t>(parts), skipping, stats);
        });
    else
        applyStores(workers, 0, 1, skipping, stats);
}

void RayCache::applyStores(std::span<CacheWorker> workers, std::size_t part, std::size_t parts, bool skipping,
                           FrameCacheStats& stats) {
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
}

void RayCache::recordFrame(Entry& e, const CacheWorker::Counters& all, ObjectCacheStats& s) {
    s.objectId = e.objectId;
    s.name = e.name;
    s.resolution = e.cube.size();
    s.levels = e.coarse.levelCount();
    // All levels, with the dependency records of an animated scene's cube.
    s.bytes = e.cube.bytes() + e.coarse.bytes() + e.blocks.size() * sizeof(RayTreeBounds);
    s.invalidPercentBefore = e.invalidPercentBefore;
    s.prefilledTexels = e.prefilledTexels;
    e.prefilledTexels = 0;
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
}

void RayCache::judgeFrame(Entry& e, const CacheWorker::Counters& all, ObjectCacheStats& s) {
    // The policy judges the frame from counts summed over every worker
    // (and, in a cluster job, every process): the same decision everywhere.
    s.state = e.policy.state();
    s.bypassedRays = all.bypassed;
    s.queuedStores = all.queuedStores;
    s.regionTests = e.regionTests;
    // A sample's texels spread over more blocks than a sixteenth of them:
    // its tests, scaled to the sample's share of full caching's.
    const std::uint64_t judgedRegionTests =
        e.policy.sampling()
            ? static_cast<std::uint64_t>(std::llround(static_cast<double>(e.regionTests) * sampleRegionTestScale(e)))
            : e.regionTests;
    e.regionTests = 0;
    const CubePolicy::Judgement judged = e.policy.afterFrame({.lookups = all.lookups,
                                                              .hits = all.hits,
                                                              .queuedStores = all.queuedStores,
                                                              .tracedTrees = all.tracedTrees,
                                                              .treeRays = all.treeRays,
                                                              .cdctSteps = all.cdctSteps,
                                                              .regionTests = judgedRegionTests,
                                                              .recordedHits = all.recordedHits,
                                                              .recordedHitRays = all.recordedHitRays});
    s.policySaving = judged.saving;
    s.policyCost = judged.cost;
    s.next = e.policy.state();
    // In an animated scene a cube standing aside empties itself: its
    // texels, unread until a probe refreshes them anyway, would cost the
    // region tests of every change (docs/caching.md, "Animated scenes").
    if (tracksDependencies_ && s.next == CubeState::Bypassed && s.state != CubeState::Bypassed) clearEntry(e);
    s.framesCaching = e.policy.framesCaching();
    s.framesSampling = e.policy.framesSampling();
    s.framesBypassed = e.policy.framesBypassed();
    s.meanTree = e.policy.meanTree();
    if (e.view.fullSize() > 0) {
        const int size = e.view.fullSize() >> e.view.afterFrame(all.lookupsByAllowedLevel);
        if (size != e.cube.size()) s.resizedTo = size;
    }
}

void RayCache::resizeViewSizedCubes(const FrameCacheStats& stats, const PartitionRunner& runPartitions) {
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
}

double RayCache::sampleRegionTestScale(const Entry& e) {
    const int n = e.cube.size();
    if (e.blocks.empty()) return 1.0;
    for (const auto& [size, scale] : sampleRegionScales_)
        if (size == n) return scale;
    // Texels in the sample, and blocks holding at least one of them: the
    // sampled runs' texels only (a sixteenth of the cube).
    constexpr int kRun = 1 << CubePolicy::kSampleRunBits;
    std::vector<unsigned char> blockSampled(e.blocks.size(), 0);
    std::uint64_t sampledTexels = 0;
    const auto texels = static_cast<int>(e.cube.texelCount());
    for (int first = 0; first < texels; first += kRun) {
        if (!CubePolicy::sampledTexel(first)) continue;
        for (int t = first; t < std::min(first + kRun, texels); ++t) {
            ++sampledTexels;
            blockSampled[static_cast<std::size_t>(blockOf(e, t))] = 1;
        }
    }
    const auto sampledBlocks = static_cast<double>(std::count(blockSampled.begin(), blockSampled.end(), 1));
    const double texelShare = static_cast<double>(sampledTexels) / static_cast<double>(texels);
    const double blockShare = sampledBlocks / static_cast<double>(e.blocks.size());
    const double scale = blockShare > 0.0 ? texelShare / blockShare : 1.0;
    sampleRegionScales_.emplace_back(n, scale);
    return scale;
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

}  // namespace raycache
