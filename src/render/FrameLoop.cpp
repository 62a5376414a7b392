#include "render/FrameLoop.h"

#include <chrono>

#include "core/Parallel.h"
#include "render/FrameRenderer.h"
#include "trace/TraceScene.h"

namespace raycache {

void renderFrames(const Scene& scene, const CameraPath& path, const RenderSettings& settings, int frameCount,
                  const FrameCallback& onFrame) {
    RayCache cache(scene, settings.cache);
    const TraceScene tracer(scene);
    const Parallel parallel(settings.threads);
    const FrameRenderer renderer(scene, tracer, settings, parallel, &cache);
    Image film(settings.width, settings.height);
    for (int frame = 0; frame < frameCount; ++frame) {
        const Camera camera = path.cameraAt(scene.camera, frame);
        const auto start = std::chrono::steady_clock::now();
        FrameResult result;
        result.frame = frame;
        result.stats = renderer.render(camera, film);
        result.milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        onFrame(result, film, cache);
    }
}

}  // namespace raycache
