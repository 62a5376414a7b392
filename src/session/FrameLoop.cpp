#include "session/FrameLoop.h"

#include <chrono>

#include "session/RenderSession.h"

namespace raycache {

void renderFrames(const Scene& scene, const CameraPath& path, const RenderSettings& settings, int frameCount,
                  const FrameCallback& onFrame, const PipelineCallback& onPipeline,
                  const std::optional<FrameTimeline>& timeline, const ProcessGroup* group) {
    const FrameTimeline times = timeline.value_or(FrameTimeline{0.0f, scene.fps});
    RenderSession session(scene, settings, group);
    if (onPipeline) onPipeline(session.description());
    Image film(settings.width, settings.height);
    for (int frame = 0; frame < frameCount; ++frame) {
        const Camera camera = path.cameraAt(scene.camera, frame);
        const auto start = std::chrono::steady_clock::now();
        session.setTime(times.timeOf(frame));
        FrameResult result;
        result.frame = frame;
        result.stats = session.render(camera, film);
        result.milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        onFrame(result, film, session.cache());
    }
}

}  // namespace raycache
