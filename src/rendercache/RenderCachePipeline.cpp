#include "rendercache/RenderCachePipeline.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/Elapsed.h"
#include "render/CacheFrame.h"
#include "render/CameraRays.h"
#include "rendercache/CameraPrediction.h"
#include "rendercache/ReconstructionBytes.h"
#include "rendercache/RenderCacheFrameContext.h"
#include "rendercache/TraceChunks.h"
#include "rendercache/ViewDependence.h"

namespace raycache {

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
    forEachTraceChunk(parallel_, pixels.size(), [&](std::size_t begin, std::size_t end, int chunk, int worker) {
        kernel_.renderCameraPixels(rays, std::span(pixels.data() + begin, end - begin),
                                   firstKey + static_cast<std::uint64_t>(chunk),
                                   scratch_[static_cast<std::size_t>(worker)], cacheFrame.worker(worker),
                                   std::span(out.data() + begin, end - begin));
    });
    return firstKey + static_cast<std::uint64_t>(traceChunkCount(pixels.size()));
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
    forEachTraceChunk(parallel, pixels.size(), [&](std::size_t begin, std::size_t end, int chunk, int worker) {
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

RenderCachePipeline::FrameContext::FrameContext(const Camera& frameCamera, Image& frameFilm, AsyncFrame* asyncFrame,
                                               const RenderSettings& settings, int frameMargin, std::size_t slots,
                                               bool cameraMoved, std::uint32_t movingFrames,
                                               const std::optional<Camera>& previousCamera, const Scene& scene)
    : camera(frameCamera), film(frameFilm), async(asyncFrame), rc(settings.renderCache), width(settings.width),
      height(settings.height), pixels(settings.width * settings.height), margin(frameMargin), imageSlots(slots),
      moved(cameraMoved), reshading{cameraMoved, settings.renderCache.reshadeInterval, movingFrames},
      wantsRequests(!asyncFrame || asyncFrame->request),
      predicts(cameraMoved && settings.renderCache.predictShare > 0.0f && wantsRequests),
      next(predicts ? predictNextCamera(*previousCamera, frameCamera) : frameCamera),
      projection(frameCamera, settings.width, settings.height), nextProjection(next, settings.width, settings.height),
      origins(objectOrigins(scene)) {}

void RenderCachePipeline::sizePool(std::size_t imageSlots, int pixels) {
    // One slot per pixel of the image and margin, plus overflow slots for
    // the predicted samples, which have no pixel yet (at most the budget,
    // at most every pixel).
    if (pool_.pixelSlots == imageSlots && pool_.capacity() == imageSlots + static_cast<std::size_t>(pixels)) return;
    pool_.reset(imageSlots, static_cast<std::size_t>(pixels), &parallel_);
    spare_.reset(imageSlots, static_cast<std::size_t>(pixels), &parallel_);
    previousCamera_.reset();
}

FrameStats RenderCachePipeline::frame(const Camera& camera, Image& film, AsyncFrame* async) {
    const int width = settings_.width, height = settings_.height;
    if (film.width() != width || film.height() != height) film = Image(width, height);
    // Meshes that moved since the last frame. (Not while the asynchronous
    // mode's tracer may be tracing: that mode takes only still scenes.)
    if (!async) kernel_.prepareFrame();
    // At least one pixel: depth culling reads every pixel's 3x3 neighbourhood.
    const int margin = std::max(
        1, static_cast<int>(std::ceil(settings_.renderCache.margin * static_cast<float>(std::max(width, height)))));
    const std::size_t imageSlots =
        static_cast<std::size_t>(width + 2 * margin) * static_cast<std::size_t>(height + 2 * margin);
    sizePool(imageSlots, width * height);
    const std::int64_t merged = async ? merge(async->batches) : 0;
    const bool moved = previousCamera_ && !(*previousCamera_ == camera);
    FrameContext f(camera, film, async, settings_, margin, imageSlots, moved, movingFrames_, previousCamera_, scene_);
    if (async) async->merged = merged;
    f.stats.pixels = f.pixels;
    scratch_.resize(static_cast<std::size_t>(parallel_.threadCount()));
    for (TileScratch& s : scratch_) s.beginFrame();

    reprojectSamples(f);
    classifyPixels(f);
    requestSamples(f);
    traceNewSamples(f);
    predictNextHoles(f);
    reshadeSamples(f);
    makeImage(f);
    return endFrame(f);
}

FrameStats RenderCachePipeline::endFrame(FrameContext& f) {
    RenderCacheStats& stats = f.stats;
    const ReconstructionBytes bytes = reconstructionBytes(f.touched);
    stats.firstRoundBytes = bytes.firstRound;
    stats.copyBytes = bytes.copy;
    stats.holesBytes = bytes.holes;
    stats.requestMapBytes = bytes.requestMaps;
    stats.fillBytes = bytes.fills;

    stats.liveSamples = f.reprojected.placed + f.newSamples;

    // The budget that would have held the target time, for the next frame.
    if (!f.async && f.rc.targetFrameMs > 0.0f && !stats.refreshedAll) {
        const double total = millisecondsSince(f.start);
        const double generation = stats.sampleGenerationMs();
        const double perRay = generation / static_cast<double>(std::max<std::int64_t>(1, stats.fresh + stats.predicted));
        const double wanted = (f.rc.targetFrameMs - (total - generation)) / std::max(perRay, 1e-6);
        adaptiveBudget_ = adaptiveBudget_ > 0.0 ? 0.5 * adaptiveBudget_ + 0.5 * wanted : wanted;
    }
    previousCamera_ = f.camera;
    if (f.moved) ++movingFrames_;
    ++frame_;
    f.frameStats.renderCache = stats;
    return f.frameStats;
}

}  // namespace raycache
