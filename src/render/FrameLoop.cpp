#include "render/FrameLoop.h"

#include <chrono>

#include "core/Parallel.h"
#include "render/FramePipeline.h"
#include "trace/TraceScene.h"

namespace raycache {

void renderFrames(const Scene& scene, const CameraPath& path, const RenderSettings& settings, int frameCount,
                  const FrameCallback& onFrame, const PipelineCallback& onPipeline) {
    RayCache cache(scene, settings.cache);
    const TraceScene tracer(scene);
    const Parallel parallel(settings.threads);
    const std::unique_ptr<FramePipeline> pipeline = makeFramePipeline(scene, tracer, settings, parallel, &cache);
    if (onPipeline) onPipeline(pipeline->description());
    Image film(settings.width, settings.height);
    for (int frame = 0; frame < frameCount; ++frame) {
        const Camera camera = path.cameraAt(scene.camera, frame);
        const auto start = std::chrono::steady_clock::now();
        FrameResult result;
        result.frame = frame;
        result.stats = pipeline->render(camera, film);
        result.milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        onFrame(result, film, cache);
    }
}

}  // namespace raycache
