#include "rendercache/RenderCachePipeline.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "core/Elapsed.h"
#include "render/CacheFrame.h"
#include "render/CameraRays.h"
#include "render/HitOnPrimitive.h"
#include "render/SurfacePoint.h"
#include "rendercache/CameraPrediction.h"
#include "rendercache/DepthCulling.h"
#include "rendercache/HoleFilling.h"
#include "rendercache/PixelStateBits.h"
#include "rendercache/ReconstructionBytes.h"
#include "rendercache/Reprojection.h"
#include "rendercache/RequestMap.h"
#include "rendercache/RowRetexturing.h"
#include "rendercache/SampleRetexturing.h"
#include "rendercache/ScreenProjection.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

// Pixels handed to the tile kernel at once: enough for full packets and
// waves, few enough to spread over the workers.
constexpr std::size_t kTraceChunk = 256;
// How many chunks of kTraceChunk make `count`.
std::size_t chunkCount(std::size_t count) { return (count + kTraceChunk - 1) / kTraceChunk; }
// Runs body(begin, end, chunk, worker) over [0, count) in chunks of
// kTraceChunk on all threads; the chunk index orders the cache's stores
// where the body traces.
template <typename Body>
void forEachChunk(const Parallel& parallel, std::size_t count, const Body& body) {
    parallel.forEachIndex(static_cast<int>(chunkCount(count)), [&](int chunk, int worker) {
        const std::size_t begin = static_cast<std::size_t>(chunk) * kTraceChunk;
        body(begin, std::min(count, begin + kTraceChunk), chunk, worker);
    });
}
// Every pixel of the image, 16x16 tile by tile (coherent packets).
void allPixels(int width, int height, std::vector<PixelCoord>& out) {
    constexpr int kTile = 16;
    out.clear();
    out.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int ty = 0; ty < height; ty += kTile)
        for (int tx = 0; tx < width; tx += kTile)
            for (int y = ty; y < std::min(height, ty + kTile); ++y)
                for (int x = tx; x < std::min(width, tx + kTile); ++x) out.push_back({x, y});
}

bool dependsOnView(const Material& m) { return m.reflects() || m.refracts() || !m.specular.isBlack(); }

}  // namespace

RenderCachePipeline::RenderCachePipeline(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                                         const Parallel& parallel, RayCache* cache)
    : scene_(scene), settings_(settings), parallel_(parallel), cache_(cache && !cache->empty() ? cache : nullptr),
      kernel_(scene, tracer, settings, cache_), movesNonRigidly_(scene.objects.size(), 0) {
    validateRenderCacheSettings(settings.renderCache);
    for (const ObjectAnimation& a : scene.animation.objects) {
        bool turnsOrScales = false;
        if (a.transform)
            for (const TransformKey& k : a.transform->keys)
                turnsOrScales = turnsOrScales || !(k.rotation == Quaternion{}) || !(k.scale == Vec3{1.0f, 1.0f, 1.0f});
        movesNonRigidly_[static_cast<std::size_t>(a.object)] = turnsOrScales || a.deformation != nullptr;
    }
}

std::string RenderCachePipeline::description() const {
    const RenderCacheSettings& rc = settings_.renderCache;
    std::ostringstream line;
    line << "pipeline: render-cache (";
    if (rc.targetFrameMs > 0.0f) line << "ray budget chosen to hold " << rc.targetFrameMs << " ms per frame";
    else line << "at most " << rc.budget * 100.0f << " % of the pixels traced per frame";
    line << ", reflections " << reprojectedReflectionsName(rc.reflections) << ")";
    return line.str();
}

void RenderCachePipeline::sceneChanged(const SceneChanges& changes) {
    std::vector<unsigned char> drop(scene_.objects.size(), 0);
    bool any = false;
    for (const int object : changes.objects)
        if (movesNonRigidly_[static_cast<std::size_t>(object)]) drop[static_cast<std::size_t>(object)] = any = true;
    if (!any) return;
    for (std::size_t slot = 0; slot < pool_.used(); ++slot) {
        int& object = pool_.point[slot].objectId;
        if (object >= 0 && drop[static_cast<std::size_t>(object)]) object = SamplePool::kEmpty;
    }
}

void RenderCachePipeline::forget() {
    pool_.reset(0, 0);
    previousCamera_.reset();
}

int RenderCachePipeline::chooseBudget(int pixels) const {
    const RenderCacheSettings& rc = settings_.renderCache;
    if (rc.targetFrameMs > 0.0f && adaptiveBudget_ > 0.0)
        return static_cast<int>(std::clamp(adaptiveBudget_, 1.0, static_cast<double>(pixels)));
    return std::max(1, static_cast<int>(std::lround(static_cast<double>(rc.budget) * pixels)));
}

void RenderCachePipeline::keep(std::size_t slot, const PrimarySample& traced, const CameraRays& rays,
                               const PixelCoord& pixel) {
    const Ray ray = rays.ray(pixel.x, pixel.y);
    SampleLook& look = pool_.look[slot];
    look.color = traced.color;
    look.age = 0;
    if (!traced.hit.hit()) {
        pool_.point[slot] = {ray.direction, SamplePool::kBackground};
        look.viewDependent = 0;
        look.textured = 0;
        return;
    }
    const SceneObject& object = scene_.objects[static_cast<std::size_t>(traced.hit.objectId)];
    pool_.point[slot] = {ray.origin + ray.direction * traced.hit.t - object.origin, traced.hit.objectId};
    look.viewDependent = dependsOnView(object.material) ? 1 : 0;
    pool_.reshade[slot] = {traced.hit.primitiveId, traced.hit.u, traced.hit.v, traced.viewIndependent, traced.litMask};
    // Only a texture varies the albedo within a primitive: elsewhere the
    // albedo at the pixel's centre is the sample's own.
    look.textured = object.material.diffuseTexture && settings_.renderCache.textureRefetch ? 1 : 0;
    if (look.textured)
        pool_.texturing[slot] = {traced.lighting, traced.color + traced.viewIndependent * -1.0f, traced.hit.primitiveId};
}

std::uint64_t RenderCachePipeline::trace(const Camera& camera, const std::vector<PixelCoord>& pixels,
                                         std::uint64_t firstKey, CacheFrame& cacheFrame,
                                         std::vector<PrimarySample>& out) {
    out.resize(pixels.size());
    const CameraRays rays(camera, settings_.width, settings_.height);
    forEachChunk(parallel_, pixels.size(), [&](std::size_t begin, std::size_t end, int chunk, int worker) {
        kernel_.renderCameraPixels(rays, std::span(pixels.data() + begin, end - begin),
                                   firstKey + static_cast<std::uint64_t>(chunk),
                                   scratch_[static_cast<std::size_t>(worker)], cacheFrame.worker(worker),
                                   std::span(out.data() + begin, end - begin));
    });
    return firstKey + static_cast<std::uint64_t>(chunkCount(pixels.size()));
}

std::int64_t RenderCachePipeline::merge(std::span<const SampleBatch> batches) {
    std::int64_t merged = 0;
    const std::size_t overflowCapacity = pool_.capacity() - pool_.pixelSlots;
    for (const SampleBatch& batch : batches) {
        // The pool is laid out for the last frame's camera: a sample traced
        // through it belongs to its pixel's slot (and replaces what it held,
        // as in render()); any other waits for reprojection to place it.
        const bool inPlace = previousCamera_ && batch.camera == *previousCamera_;
        const CameraRays rays(batch.camera, settings_.width, settings_.height);
        for (std::size_t i = 0; i < batch.samples.size(); ++i) {
            const PixelCoord p = batch.pixels[i];
            std::size_t slot = 0;
            if (inPlace) slot = image_.pixelIndex(p.x, p.y);
            else if (pool_.overflowUsed < overflowCapacity) slot = pool_.takeOverflowSlot();
            else continue;  // no room left this frame: its pixel will be asked for again
            keep(slot, batch.samples[i], rays, p);
            ++merged;
        }
    }
    return merged;
}

RayCounts RenderCachePipeline::traceSamples(const Camera& camera, std::span<const PixelCoord> pixels,
                                            const Parallel& parallel, std::vector<TileScratch>& scratch,
                                            std::span<PrimarySample> out) {
    scratch.resize(static_cast<std::size_t>(parallel.threadCount()));
    for (TileScratch& s : scratch) s.beginFrame();
    std::unique_lock<std::mutex> cacheLock(cacheMutex_, std::defer_lock);
    if (cache_) cacheLock.lock();
    CacheFrame cacheFrame(cache_, parallel.threadCount());
    const CameraRays rays(camera, settings_.width, settings_.height);
    forEachChunk(parallel, pixels.size(), [&](std::size_t begin, std::size_t end, int chunk, int worker) {
        kernel_.renderCameraPixels(rays, pixels.subspan(begin, end - begin), static_cast<std::uint64_t>(chunk),
                                   scratch[static_cast<std::size_t>(worker)], cacheFrame.worker(worker),
                                   out.subspan(begin, end - begin));
    });
    RayCounts counts;
    for (const TileScratch& s : scratch) counts += s.counts;
    cacheFrame.finish(kernel_, parallel, counts);
    return counts;
}

FrameStats RenderCachePipeline::render(const Camera& camera, Image& film) { return frame(camera, film, nullptr); }

FrameStats RenderCachePipeline::reconstruct(const Camera& camera, Image& film, std::span<const SampleBatch> batches,
                                            int ageStep, int budget, SampleRequest* request, std::int64_t& merged) {
    AsyncFrame async{batches, ageStep, budget, request, 0};
    FrameStats stats = frame(camera, film, &async);
    merged = async.merged;
    return stats;
}

FrameStats RenderCachePipeline::frame(const Camera& camera, Image& film, AsyncFrame* async) {
    const RenderCacheSettings& rc = settings_.renderCache;
    const int width = settings_.width, height = settings_.height;
    const int pixels = width * height;
    if (film.width() != width || film.height() != height) film = Image(width, height);
    // Meshes that moved since the last frame. (Not while the asynchronous
    // mode's tracer may be tracing: that mode takes only still scenes.)
    if (!async) kernel_.prepareFrame();
    const auto frameStart = Clock::now();
    RenderCacheStats stats;
    stats.pixels = pixels;

    // At least one pixel: depth culling reads every pixel's 3x3 neighbourhood.
    const int margin =
        std::max(1, static_cast<int>(std::ceil(rc.margin * static_cast<float>(std::max(width, height)))));
    const std::size_t imageSlots =
        static_cast<std::size_t>(width + 2 * margin) * static_cast<std::size_t>(height + 2 * margin);
    // One slot per pixel of the image and margin, plus overflow slots for
    // the predicted samples, which have no pixel yet (at most the budget,
    // at most every pixel).
    if (pool_.pixelSlots != imageSlots || pool_.capacity() != imageSlots + static_cast<std::size_t>(pixels)) {
        pool_.reset(imageSlots, static_cast<std::size_t>(pixels));
        spare_.reset(imageSlots, static_cast<std::size_t>(pixels));
        previousCamera_.reset();
    }
    if (async) async->merged = merge(async->batches);
    const bool moved = previousCamera_ && !(*previousCamera_ == camera);
    // The asynchronous mode asks for samples only when the last request is
    // traced and merged; meanwhile it makes no request map.
    const bool wantsRequests = !async || async->request;
    std::int64_t newSamples = 0;  // taking a slot no sample held: in a hole, or predicted
    scratch_.resize(static_cast<std::size_t>(parallel_.threadCount()));
    for (TileScratch& s : scratch_) s.beginFrame();

    // What the reconstruction passes touch, for the counted bytes they move
    // (ReconstructionBytes.h).
    ReconstructionCounts touched;
    touched.width = width;
    touched.height = height;
    touched.pixelSlots = static_cast<std::int64_t>(imageSlots);
    touched.usedSlots = static_cast<std::int64_t>(pool_.used());

    // Reprojection.
    auto start = Clock::now();
    const ScreenProjection projection(camera, width, height);
    const std::vector<Vec3> origins = objectOrigins(scene_);
    image_.reset(width, height, margin);
    // The camera of the next frame, for predictive sampling: the samples
    // are projected through it in the same pass.
    const bool predicts = moved && rc.predictShare > 0.0f && wantsRequests;
    const Camera next = predicts ? predictNextCamera(*previousCamera_, camera) : camera;
    const ScreenProjection nextProjection(next, width, height);
    const ReprojectionCounts reprojected =
        reproject(pool_, spare_, scene_, projection, rc.maxAge, image_, parallel_, reprojectionScratch_,
                  predicts ? &nextProjection : nullptr, &nextPixel_, async ? async->ageStep : 1);
    std::swap(pool_, spare_);
    stats.evicted = reprojected.evicted;
    stats.lost = reprojected.lost;
    stats.reprojectMs = millisecondsSince(start);
    touched.liveSamples = reprojected.live;
    touched.offered = reprojected.offered;
    touched.farOffers = reprojected.farOffers;
    touched.secondChances = reprojected.secondChances;
    touched.predicts = predicts;
    touched.placed = reprojected.placed;
    touched.moved = reprojected.moved;
    touched.reshadeCopied = reprojected.reshadeCopied;
    touched.texturingCopied = reprojected.texturingCopied;

    // Depth culling, holes, the priority and request maps.
    start = Clock::now();
    std::vector<PixelState>& state = overlays_.state;
    state.resize(static_cast<std::size_t>(pixels));
    std::vector<float>& priority = priority_;
    priority.resize(static_cast<std::size_t>(pixels));  // every pixel written below
    // One pass: holes, depth culling (a still camera puts every sample back
    // where it was traced: nothing to cull) and priorities. Counts per row
    // go to locals, written once (no false sharing).
    const bool cull = moved && rc.depthCullThreshold > 0.0f;
    std::vector<std::int64_t> holesPerRow(static_cast<std::size_t>(height), 0);
    std::vector<std::int64_t> culledPerRow(static_cast<std::size_t>(height), 0);
    std::vector<std::int64_t> reprojectedPerRow(static_cast<std::size_t>(height), 0);
    std::vector<std::int64_t> texturedPerRow(static_cast<std::size_t>(height), 0);
    const float agePriority = 0.5f / static_cast<float>(rc.maxAge);
    // Textured samples show the albedo their pixel's centre sees
    // (SampleRetexturing); a still camera puts every sample back where it was
    // traced, so they already do.
    const bool retexture = moved && rc.textureRefetch;
    const CameraRays centreRays(camera, width, height);
    // Each row's culling decisions, taken before the row is classified.
    std::vector<unsigned char>& hiddenPerPixel = bytes_;
    if (cull) hiddenPerPixel.resize(static_cast<std::size_t>(pixels));
    parallel_.forEachIndex(height, [&](int y, int) {
        std::int64_t rowHoles = 0, rowCulled = 0, rowReprojected = 0, rowTextured = 0;
        // Addresses and sizes in locals (through the members the compiler
        // reloaded them after every store).
        const auto stride = static_cast<std::size_t>(image_.stride());
        const std::size_t rowSlot = image_.pixelIndex(0, y);
        const std::uint32_t* const keys = image_.keyData() + rowSlot;
        SampleLook* const looks = pool_.look.data() + rowSlot;
        const SamplePoint* const points = pool_.point.data() + rowSlot;
        const SampleTexturing* const texturings = pool_.texturing.data() + rowSlot;
        PixelState* const rowState = state.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
        float* const rowPriority = priority.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
        unsigned char* const hidden =
            cull ? hiddenPerPixel.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) : nullptr;
        if (cull) hiddenByNearerKeysRow(keys - stride, keys, keys + stride, width, rc.depthCullThreshold, hidden);
        // The frame's flags in locals too: captured by reference, each was
        // loaded through the closure for every pixel.
        const bool culling = cull, refetching = retexture;
        const float ageShare = agePriority;
        const int columns = width;
        RowRetexturing retexturing(scene_.objects, centreRays, y);
        for (int x = 0; x < columns; ++x) {
            const auto i = static_cast<std::size_t>(x);
            if (keys[x] == PointImage::emptyKey()) {
                rowState[i] = PixelState::Hole;
                rowPriority[i] = 1.0f;
                ++rowHoles;
            } else if (culling && hidden[x]) {
                rowState[i] = PixelState::Culled;
                rowPriority[i] = 1.0f;
                ++rowCulled;
            } else {
                rowState[i] = PixelState::Reprojected;
                SampleLook& look = looks[i];
                rowPriority[i] = ageShare * static_cast<float>(look.age);
                // Re-fetched below when the frame re-fetches; added without a
                // branch (a counter inside the re-fetch's branch cost this
                // pass 4 % of its instructions).
                rowTextured += look.textured ? 1 : 0;
                if (refetching && look.textured) {
                    const int object = points[i].objectId;
                    const auto distance = [&] {
                        return length(scene_.objects[static_cast<std::size_t>(object)].origin + points[i].position -
                                      camera.position);
                    };
                    // Where the centre misses the sample's primitive (its
                    // edge, a silhouette), the stored colour, and a ray sooner.
                    if (!retexturing.color(x, object, texturings[i], distance, look.color))
                        rowPriority[i] = std::max(rowPriority[i], kMissedPrimitivePriority);
                }
                ++rowReprojected;
            }
        }
        reprojectedPerRow[static_cast<std::size_t>(y)] = rowReprojected;
        holesPerRow[static_cast<std::size_t>(y)] = rowHoles + rowCulled;
        culledPerRow[static_cast<std::size_t>(y)] = rowCulled;
        texturedPerRow[static_cast<std::size_t>(y)] = rowTextured;
    });
    for (std::int64_t c : culledPerRow) stats.culled += c;
    for (std::int64_t r : reprojectedPerRow) stats.reprojected += r;
    std::int64_t holes = 0;
    for (std::int64_t h : holesPerRow) holes += h;
    stats.holes = holes;
    touched.holes = holes;
    touched.culls = cull;
    if (retexture)
        for (std::int64_t r : texturedPerRow) touched.retextured += r;
    stats.refreshedAll = !previousCamera_ || static_cast<double>(holes) > static_cast<double>(rc.refreshAllHoleShare) * pixels;
    const int budget = stats.refreshedAll                  ? pixels
                       : async && async->budget > 0 ? std::min(async->budget, pixels)
                                                    : chooseBudget(pixels);
    stats.budget = wantsRequests ? budget : 0;
    const int predictedBudget =
        (moved && !stats.refreshedAll && wantsRequests)
            ? static_cast<int>(std::lround(static_cast<double>(budget) * rc.predictShare))
            : 0;
    RequestMap& requests = overlays_.requests;
    overlays_.width = width;
    overlays_.height = height;
    if (!wantsRequests) {
        requests.pixels.clear();
        requests.tileRequests.clear();
        requests.tilePriority.clear();
    } else if (stats.refreshedAll) {
        allPixels(width, height, requests.pixels);
        requests.tileRequests.clear();
        requests.tilePriority.clear();
    } else {
        buildRequestMap(priority, width, height, rc.requestTileSize, rc.alpha, budget - predictedBudget, rc.seed,
                        frame_, requests, parallel_);
    }
    stats.mapsMs = millisecondsSince(start);
    touched.everyPixelRequested = wantsRequests && stats.refreshedAll;
    touched.requestMap = wantsRequests && !stats.refreshedAll;
    if (touched.requestMap) {
        touched.tiles = static_cast<std::int64_t>(requests.tileRequests.size());
        touched.requested = static_cast<std::int64_t>(requests.pixels.size());
        touched.pixelsInRequestedTiles = pixelsInTilesWithRequests(requests, width, height);
    }

    // New samples through this frame's camera, replacing what their pixels
    // held; the asynchronous mode hands the request to its tracer instead.
    start = Clock::now();
    std::unique_lock<std::mutex> cacheLock(cacheMutex_, std::defer_lock);
    std::optional<CacheFrame> cacheFrame;
    std::vector<PrimarySample>& traced = traced_;
    std::uint64_t key = 0;
    if (async) {
        traced.clear();
        if (async->request) {
            async->request->camera = camera;
            async->request->pixels = requests.pixels;
            async->request->predicted.clear();
            async->request->refreshesAll = stats.refreshedAll;
        }
    } else {
        cacheFrame.emplace(cache_, parallel_.threadCount());
        key = trace(camera, requests.pixels, 0, *cacheFrame, traced);
    }
    if (!async) {
        // On all threads: the requested pixels are distinct, and each one's
        // writes touch only its own slot, key and state. (On one thread
        // this loop's cache misses cost about 4 ms per frame at 1024².)
        const CameraRays rays(camera, width, height);
        std::vector<std::int64_t> newPerChunk(chunkCount(traced.size()), 0);
        std::vector<std::int64_t> replacedPerChunk(chunkCount(traced.size()), 0);
        forEachChunk(parallel_, traced.size(), [&](std::size_t begin, std::size_t end, int chunk, int) {
            std::int64_t fresh = 0, replaced = 0;
            for (std::size_t i = begin; i < end; ++i) {
                const PixelCoord p = requests.pixels[i];
                const std::size_t slot = image_.pixelIndex(p.x, p.y);
                fresh += image_.hasSample(p.x, p.y) ? 0 : 1;
                keep(slot, traced[i], rays, p);
                int px, py;
                float depth = std::numeric_limits<float>::infinity();  // a camera ray's hit is never behind the eye
                projectSample(pool_, slot, origins, projection, px, py, depth);
                // Placed where it was traced, whatever rounding says about the reprojection.
                image_.place(p.x, p.y, depth);
                PixelState& s = state[static_cast<std::size_t>(p.y * width + p.x)];
                replaced += s == PixelState::Reprojected ? 1 : 0;
                s = PixelState::Fresh;
                if (predictedBudget > 0)
                    nextPixel_[slot] = imagePixelThrough(pool_, slot, origins, nextProjection, width, height);
            }
            newPerChunk[static_cast<std::size_t>(chunk)] = fresh;
            replacedPerChunk[static_cast<std::size_t>(chunk)] = replaced;
        });
        for (std::int64_t n : newPerChunk) newSamples += n;
        for (std::int64_t n : replacedPerChunk) stats.reprojected -= n;
    }
    stats.fresh = static_cast<std::int64_t>(traced.size());
    stats.traceMs = millisecondsSince(start);

    // Predictive sampling: where the next camera will find holes.
    if (predictedBudget > 0) {
        start = Clock::now();
        // Where the samples land through the next camera was found by
        // reproject() (fresh samples: when kept); every sample is in a
        // pixel slot until the predicted ones are kept below.
        std::vector<unsigned char>& covered = bytes_;
        covered.assign(static_cast<std::size_t>(pixels), 0);
        const std::size_t n = pool_.pixelSlots;
        constexpr std::size_t kChunk = 16384;
        parallel_.forEachIndex(static_cast<int>((n + kChunk - 1) / kChunk), [&](int chunk, int) {
            const std::size_t end = std::min(n, (static_cast<std::size_t>(chunk) + 1) * kChunk);
            for (std::size_t slot = static_cast<std::size_t>(chunk) * kChunk; slot < end; ++slot)
                if (const std::int32_t pixel = nextPixel_[slot]; pixel >= 0)
                    std::atomic_ref<unsigned char>(covered[static_cast<std::size_t>(pixel)])
                        .store(1, std::memory_order_relaxed);
        });
        parallel_.forEachIndex(height, [&](int y, int) {
            for (auto i = static_cast<std::size_t>(y * width); i < static_cast<std::size_t>((y + 1) * width); ++i)
                priority[i] = covered[i] ? 0.0f : 1.0f;
        });
        buildRequestMap(priority, width, height, rc.requestTileSize, 1.0f, predictedBudget, rc.seed ^ 0x5eed,
                        frame_, predictedRequests_, parallel_);
        const std::size_t offered = predictedRequests_.pixels.size();
        // Only holes: a tile without any gets no ray even if rounding offered one.
        std::erase_if(predictedRequests_.pixels, [&](const PixelCoord& p) {
            return covered[static_cast<std::size_t>(p.y * width + p.x)] != 0;
        });
        stats.mapsMs += millisecondsSince(start);
        touched.predictionMap = true;
        touched.predictedOffered = static_cast<std::int64_t>(offered);
        touched.predictedKept = static_cast<std::int64_t>(predictedRequests_.pixels.size());
        touched.pixelsInPredictedTiles = pixelsInTilesWithRequests(predictedRequests_, width, height);
        start = Clock::now();
        if (async) {
            async->request->nextCamera = next;
            async->request->predicted = predictedRequests_.pixels;
        } else {
            key = trace(next, predictedRequests_.pixels, key, *cacheFrame, traced);
            const CameraRays rays(next, width, height);
            for (std::size_t i = 0; i < traced.size(); ++i)
                keep(pool_.takeOverflowSlot(), traced[i], rays, predictedRequests_.pixels[i]);
            newSamples += static_cast<std::int64_t>(traced.size());
            stats.predicted = static_cast<std::int64_t>(traced.size());
        }
        stats.traceMs += millisecondsSince(start);
    }
    // The display's cache frame (its reshading's lookups and stores) waits
    // for the tracer's to end.
    if (async) {
        if (cache_) cacheLock.lock();
        cacheFrame.emplace(cache_, parallel_.threadCount());
    }

    // Reflections, refractions and highlights of reprojected samples, from the new eye.
    start = Clock::now();
    if (moved && rc.reflections == ReprojectedReflections::Reshade) {
        std::vector<ReshadeRequest>& reshade = reshade_;
        std::vector<std::uint32_t>& slots = reshadeSlots_;
        // On all threads, in pixel order (the order keys the cache's
        // stores): count each row's samples, then write each row's at its
        // offset. (One thread walking the image cost 5-9 ms a frame at 1024².)
        const auto reshaded = [&](int x, int y) {
            return state[static_cast<std::size_t>(y * width + x)] == PixelState::Reprojected &&
                   pool_.look[image_.pixelIndex(x, y)].viewDependent;
        };
        std::vector<std::size_t> rowStart(static_cast<std::size_t>(height) + 1, 0);
        parallel_.forEachIndex(height, [&](int y, int) {
            std::size_t count = 0;
            for (int x = 0; x < width; ++x) count += reshaded(x, y) ? 1 : 0;
            rowStart[static_cast<std::size_t>(y) + 1] = count;
        });
        for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) rowStart[y + 1] += rowStart[y];
        reshade.resize(rowStart.back());
        slots.resize(rowStart.back());
        const CameraRays pixelRays(camera, width, height);
        parallel_.forEachIndex(height, [&](int y, int) {
            std::size_t i = rowStart[static_cast<std::size_t>(y)];
            for (int x = 0; x < width; ++x) {
                if (!reshaded(x, y)) continue;
                const auto slot = static_cast<std::uint32_t>(image_.pixelIndex(x, y));
                const int object = pool_.point[slot].objectId;
                const SceneObject& sceneObject = scene_.objects[static_cast<std::size_t>(object)];
                const Vec3 point = sceneObject.origin + pool_.point[slot].position;
                const ReshadeInputs& inputs = pool_.reshade[slot];
                const Vec3 toPoint = point - camera.position;
                const float distance = length(toPoint);
                ReshadeRequest& r = reshade[i];
                r = ReshadeRequest{};
                // Shaded where the pixel's centre meets the sample's surface:
                // a reflection on a curved mirror changes within a pixel, so
                // shading the sample's own point (up to a pixel off) smears it.
                // Where that ray misses the surface, the sample's point.
                const Ray centreRay = pixelRays.ray(x, y);
                r.viewIndependent = inputs.viewIndependent;
                if (const auto atCentre = hitOnPrimitive(sceneObject, object, inputs.primitiveId, centreRay, distance)) {
                    r.ray = centreRay;
                    r.hit = *atCentre;
                    // A textured sample's diffuse part with the albedo seen there.
                    if (pool_.look[slot].textured)
                        r.viewIndependent = albedoAtHit(sceneObject, centreRay, *atCentre) * pool_.texturing[slot].lighting;
                } else {
                    r.ray = Ray{camera.position, toPoint * (1.0f / distance)};
                    r.hit = TraceHit{distance, object, inputs.primitiveId, inputs.baryU, inputs.baryV};
                }
                r.litMask = inputs.litMask;
                slots[i++] = slot;
            }
        });
        std::vector<Rgb>& colors = reshadeColors_;
        colors.resize(reshade.size());
        forEachChunk(parallel_, reshade.size(), [&](std::size_t begin, std::size_t end, int chunk, int worker) {
            kernel_.reshadeSurfaces(std::span(reshade.data() + begin, end - begin),
                                    key + static_cast<std::uint64_t>(chunk), scratch_[static_cast<std::size_t>(worker)],
                                    cacheFrame->worker(worker), std::span(colors.data() + begin, end - begin));
        });
        forEachChunk(parallel_, slots.size(), [&](std::size_t begin, std::size_t end, int, int) {
            for (std::size_t i = begin; i < end; ++i) pool_.look[slots[i]].color = colors[i];
        });
        stats.reshaded = static_cast<std::int64_t>(slots.size());
    }
    stats.reshadeMs = millisecondsSince(start);
    // The stores queued by this frame's rays are merged: part of tracing them.
    start = Clock::now();
    FrameStats frameStats;
    for (const TileScratch& s : scratch_) frameStats.rays += s.counts;
    frameStats.cache = cacheFrame->finish(kernel_, parallel_, frameStats.rays);
    if (cacheLock.owns_lock()) cacheLock.unlock();
    stats.traceMs += millisecondsSince(start);

    // The image: samples where there are, the filters elsewhere, in one
    // pass that reads the samples' colours from the pool. (A pass of its
    // own that copied them into the film first cost a write and a read of
    // the whole film.)
    start = Clock::now();
    const CameraRays rays(camera, width, height);
    // A background sample shows what it saw, like any other: looking up an
    // image environment along every pixel's ray again cost 12 ms per frame
    // at 1024x1024 on `room`.
    const SampleColors colors{pool_.look.data(), image_.pixelIndex(0, 0), static_cast<std::size_t>(image_.stride())};
    // Edge-aware: a hole takes the samples of one surface around it.
    const SampleSurfaces surfaces{&image_, pool_.point.data(), image_.pixelIndex(0, 0),
                                  static_cast<std::size_t>(image_.stride())};
    const FillCounts filled = fillHoles(state, film, parallel_, &bytes_, &colors, &surfaces, &fillSource_);
    // A hole filled from a textured surface shows that surface's texture at
    // its own centre: the lighting and rest of the group's first sample,
    // the albedo where the hole's centre ray meets that sample's primitive
    // (on a checkerboard floor the filters' mean of neighbouring squares is
    // a grey that neither square has). Where it misses, the filter's mean.
    // The filled holes are found a word of pixels at a time (PixelStateBits):
    // testing every pixel's state cost twice what re-fetching the holes did.
    std::vector<std::vector<std::uint64_t>> filledPerWorker(static_cast<std::size_t>(parallel_.threadCount()));
    std::vector<std::int64_t> retexturedHolesPerRow(static_cast<std::size_t>(height), 0);
    touched.filledRefetch = rc.textureRefetch && filled.filled3x3 + filled.filled7x7 > 0;
    if (touched.filledRefetch)
        parallel_.forEachIndex(height, [&](int y, int worker) {
            std::vector<std::uint64_t>& filledBits = filledPerWorker[static_cast<std::size_t>(worker)];
            filledBits.resize(pixelStateWords(width));
            pixelStateBits(state.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width), width,
                           PixelState::Filled3x3, PixelState::Filled7x7, filledBits.data());
            if (std::all_of(filledBits.begin(), filledBits.end(), [](std::uint64_t b) { return b == 0; })) return;
            RowRetexturing retexturing(scene_.objects, rays, y);
            std::int64_t retexturedHoles = 0;
            forEachPixelSet(filledBits.data(), width, [&](int x) {
                const auto i = static_cast<std::size_t>(y * width + x);
                const int source = fillSource_[i];
                const std::size_t slot = image_.pixelIndex(source % width, source / width);
                if (!pool_.look[slot].textured) return;
                ++retexturedHoles;
                const int object = pool_.point[slot].objectId;
                const auto distance = [&] {
                    return length(scene_.objects[static_cast<std::size_t>(object)].origin + pool_.point[slot].position -
                                  camera.position);
                };
                retexturing.color(x, object, pool_.texturing[slot], distance, film.at(x, y));
            });
            retexturedHolesPerRow[static_cast<std::size_t>(y)] = retexturedHoles;
        });
    stats.filled3x3 = filled.filled3x3;
    stats.filled7x7 = filled.filled7x7;
    stats.unfilled = filled.unfilled;
    if (filled.unfilled > 0)
        parallel_.forEachIndex(height, [&](int y, int) {
            // There are few (a handful a frame): memchr finds them a register at a time.
            const auto* const row =
                reinterpret_cast<const unsigned char*>(state.data()) + static_cast<std::size_t>(y * width);
            const auto unfilled = static_cast<unsigned char>(PixelState::Unfilled);
            for (const void* at = std::memchr(row, unfilled, static_cast<std::size_t>(width)); at;) {
                const auto x = static_cast<int>(static_cast<const unsigned char*>(at) - row);
                film.at(x, y) = kernel_.shading().background(rays.ray(x, y));
                at = std::memchr(row + x + 1, unfilled, static_cast<std::size_t>(width - x - 1));
            }
        });
    stats.filterMs = millisecondsSince(start);
    touched.filled3x3 = filled.filled3x3;
    touched.filled7x7 = filled.filled7x7;
    touched.unfilled = filled.unfilled;
    touched.samplesRead = filled.samplesRead;
    touched.rowsWithHoles = filled.rowsWithHoles;
    for (std::int64_t r : retexturedHolesPerRow) touched.retexturedHoles += r;
    const ReconstructionBytes bytes = reconstructionBytes(touched);
    stats.firstRoundBytes = bytes.firstRound;
    stats.copyBytes = bytes.copy;
    stats.holesBytes = bytes.holes;
    stats.requestMapBytes = bytes.requestMaps;
    stats.fillBytes = bytes.fills;

    stats.liveSamples = reprojected.placed + newSamples;

    // The budget that would have held the target time, for the next frame.
    if (!async && rc.targetFrameMs > 0.0f && !stats.refreshedAll) {
        const double total = millisecondsSince(frameStart);
        const double generation = stats.sampleGenerationMs();
        const double perRay = generation / static_cast<double>(std::max<std::int64_t>(1, stats.fresh + stats.predicted));
        const double wanted = (rc.targetFrameMs - (total - generation)) / std::max(perRay, 1e-6);
        adaptiveBudget_ = adaptiveBudget_ > 0.0 ? 0.5 * adaptiveBudget_ + 0.5 * wanted : wanted;
    }
    previousCamera_ = camera;
    ++frame_;
    frameStats.renderCache = stats;
    return frameStats;
}

}  // namespace raycache
