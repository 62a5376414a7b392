#include "bench/AsyncDisplayMeasurement.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "core/Errors.h"

namespace raycache {
namespace {

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

AsyncDisplayResult measureAsyncDisplay(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                                       RayCache* cache, int frames, double reshadeBudgetMs) {
    AsyncRenderCache display(scene, tracer, settings, cache, splitRenderCacheThreads(settings.threads));
    display.setReshadeBudgetMs(reshadeBudgetMs);
    Image film;
    // The first display frame asks for every pixel; timing starts once that
    // request is traced and merged, as a viewer's user would see it.
    const Camera first = scene.cameraPath.cameraAt(scene.camera, 0);
    // (reconstruct() rethrows what stopped the tracer.)
    display.reconstruct(first, film);
    while (display.counts().requests < 1) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        display.reconstruct(first, film);
    }
    display.reconstruct(first, film);

    AsyncDisplayResult result;
    std::vector<double> reconstruction, reshade;
    const AsyncTraceCounts before = display.counts();
    const auto start = std::chrono::steady_clock::now();
    for (int f = 1; f <= frames; ++f) {
        const FrameStats stats = display.reconstruct(scene.cameraPath.cameraAt(scene.camera, f), film);
        if (!stats.renderCache) throw RuntimeError("the asynchronous Render Cache returned no statistics");
        reconstruction.push_back(stats.renderCache->reconstructionMs());
        reshade.push_back(stats.renderCache->reshadeMs);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const AsyncTraceCounts after = display.counts();
    result.displayFrames = frames;
    result.displayFps = seconds > 0.0 ? frames / seconds : 0.0;
    result.samplesPerSecond = seconds > 0.0 ? static_cast<double>(after.samples - before.samples) / seconds : 0.0;
    result.medianReconstructionMs = median(reconstruction);
    result.medianReshadeMs = median(reshade);
    result.lastReshadeInterval = display.reshadeInterval();
    return result;
}

}  // namespace raycache
