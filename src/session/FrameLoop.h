#pragma once
// Renders a scene along a camera path, frame after frame, timing each frame.
#include <functional>
#include <optional>
#include <string>

#include "cache/RayCache.h"
#include "core/Image.h"
#include "core/ProcessGroup.h"
#include "render/FrameStats.h"
#include "render/RenderSettings.h"
#include "scene/Scene.h"

namespace raycache {

struct FrameResult {
    int frame = 0;              // 0-based
    double milliseconds = 0.0;  // wall time of the render, excluding the callback
    FrameStats stats;
};

// Builds the acceleration structure and the caches (settings.cache) once,
// then renders frames [0, frameCount) with cameras from `path` applied to
// scene.camera, calling onFrame after each. Throws InputError for invalid
// cache settings before rendering anything. onFrame also sees the caches as
// they stand after the frame (e.g. to write a view of a cube).
// onPipeline, when given, is called once before the first frame with the
// line that says which pipeline renders (render/FramePipeline.h).
// Which moment of an animated scene each frame shows: frame f shows
// startTime + f / fps seconds.
struct FrameTimeline {
    float startTime = 0.0f;
    float fps = 30.0f;
    float timeOf(int frame) const { return startTime + static_cast<float>(frame) / fps; }
};

using FrameCallback = std::function<void(const FrameResult&, const Image& film, const RayCache& caches)>;
using PipelineCallback = std::function<void(const std::string& description)>;
// An animated scene is posed at timeline.timeOf(frame) before each frame
// (default: from 0 at the scene's fps); the frame's time includes that update.
// With `group` of several processes, each frame's tiles are shared among
// them (every process must call this with the same arguments).
void renderFrames(const Scene& scene, const CameraPath& path, const RenderSettings& settings, int frameCount,
                  const FrameCallback& onFrame, const PipelineCallback& onPipeline = {},
                  const std::optional<FrameTimeline>& timeline = std::nullopt, const ProcessGroup* group = nullptr);

}  // namespace raycache
