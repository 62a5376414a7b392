// RenderCachePipeline's reshading (`--rc-reflections reshade`): the
// highlights, reflections and refractions of reprojected samples on
// mirrors, glass and glossy surfaces evaluated again from the new eye, where
// the pixel's centre meets the sample's surface; then the caches' frame ends
// (the stores queued by this frame's rays are merged).
#include <atomic>

#include "core/Elapsed.h"
#include "core/Errors.h"
#include "render/CameraRays.h"
#include "render/HitOnPrimitive.h"
#include "render/SurfacePoint.h"
#include "rendercache/PixelStateBits.h"
#include "rendercache/RenderCacheFrameContext.h"
#include "rendercache/TraceChunks.h"

namespace raycache {

void RenderCachePipeline::reshadeSamples(FrameContext& f) {
    // The display's cache frame (its reshading's lookups and stores) waits
    // for the tracer's to end.
    if (f.async) {
        f.cacheLock = std::unique_lock<std::mutex>(cacheMutex_, std::defer_lock);
        if (cache_) f.cacheLock.lock();
        f.cacheFrame.emplace(cache_, parallel_.threadCount());
    }
    auto start = std::chrono::steady_clock::now();
    if (f.reshading.any() && f.rc.reflections == ReprojectedReflections::Reshade) {
        const int width = f.width, height = f.height;
        const Camera& camera = f.camera;
        const std::vector<PixelState>& state = overlays_.state;
        std::vector<ReshadeRequest>& reshade = reshade_;
        std::vector<std::uint32_t>& slots = reshadeSlots_;
        // On all threads, in pixel order (the order keys the cache's
        // stores): each row's samples written at its offset, from the counts
        // classifyPixels took on its trip over the image: one thread walking
        // the image was a large share of the frame, and a walk of its own to
        // count them a visible one (docs/log/2026-11-28-render-cache-earns-its-place.md).
        // The samples are those classifyPixels chose, less those a new
        // sample replaced since (no longer Reprojected).
        const std::size_t words = pixelStateWords(width);
        std::vector<std::size_t>& rowStart = reshadeRowStart_;
        for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) rowStart[y + 1] += rowStart[y];
        reshade.resize(rowStart.back());
        slots.resize(rowStart.back());
        const CameraRays pixelRays(camera, width, height);
        std::atomic<bool> miscounted{false};
        parallel_.forEachIndex(height, [&](int y, int) {
            std::size_t i = rowStart[static_cast<std::size_t>(y)];
            PrimitiveHits centreHits;
            forEachPixelSet(reshadeBits_.data() + static_cast<std::size_t>(y) * words, width, [&](int x) {
                if (state[static_cast<std::size_t>(y * width + x)] != PixelState::Reprojected) return;
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
                if (const auto atCentre =
                        centreHits.hit(sceneObject, object, inputs.primitiveId, centreRay, distance)) {
                    r.ray = centreRay;
                    r.hit = *atCentre;
                    // A textured sample's diffuse part with the albedo seen there.
                    if (pool_.look[slot].textured)
                        r.viewIndependent =
                            albedoAtHit(sceneObject, centreRay, *atCentre) * pool_.texturing[slot].lighting;
                } else {
                    r.ray = Ray{camera.position, toPoint * (1.0f / distance)};
                    r.hit = TraceHit{distance, object, inputs.primitiveId, inputs.baryU, inputs.baryV};
                }
                r.litMask = inputs.litMask;
                slots[i++] = slot;
            });
            if (i != rowStart[static_cast<std::size_t>(y) + 1]) miscounted.store(true, std::memory_order_relaxed);
        });
        if (miscounted.load()) throw RuntimeError("Render Cache: reshading's row counts do not match the image");
        std::vector<Rgb>& colors = reshadeColors_;
        colors.resize(reshade.size());
        forEachTraceChunk(parallel_, reshade.size(), [&](std::size_t begin, std::size_t end, int chunk, int worker) {
            kernel_.reshadeSurfaces(std::span(reshade.data() + begin, end - begin),
                                    f.key + static_cast<std::uint64_t>(chunk),
                                    scratch_[static_cast<std::size_t>(worker)], f.cacheFrame->worker(worker),
                                    std::span(colors.data() + begin, end - begin));
        });
        forEachTraceChunk(parallel_, slots.size(), [&](std::size_t begin, std::size_t end, int, int) {
            for (std::size_t i = begin; i < end; ++i) {
                pool_.look[slots[i]].color = colors[i];
                pool_.look[slots[i]].viewDependent = kViewDependent;
            }
        });
        f.stats.reshaded = static_cast<std::int64_t>(slots.size());
    }
    f.stats.reshadeMs = millisecondsSince(start);
    // The stores queued by this frame's rays are merged: part of tracing them.
    start = std::chrono::steady_clock::now();
    for (const TileScratch& s : scratch_) f.frameStats.rays += s.counts;
    f.frameStats.cache = f.cacheFrame->finish(kernel_, parallel_, f.frameStats.rays);
    if (f.cacheLock.owns_lock()) f.cacheLock.unlock();
    f.stats.traceMs += millisecondsSince(start);
}

}  // namespace raycache
