#pragma once
// Offline multi-frame renders over the processes of a job: whole frames,
// frame f on process f mod n. Only for frames that do not depend on each
// other: with caches on, a frame's cubes hold what every earlier frame
// stored, and the Render Cache reprojects the previous frame's samples, so
// those frames must be made in order (the tiles of each are shared instead,
// render/FrameRenderer.h; docs/cluster.md).
#include <functional>

#include "core/ProcessGroup.h"
#include "session/FrameLoop.h"

namespace raycache {

// True when renderFramesAcrossProcesses may render these frames: no object
// is cached under the settings and the pipeline keeps no state between frames.
bool framesAreIndependent(const Scene& scene, const RenderSettings& settings);

// Renders frames [0, frameCount) spread over `group` (each process with its
// own single-process session and threads), then, on process 0 only, calls
// onFrame for every frame in order with the frame's statistics (ClusterStats
// says "whole frames") and, when needsFilm(frame), its image gathered from
// the process that made it (otherwise `film` holds some other frame). The
// images equal renderFrames'; the scene-update statistics of an animated
// scene count from the frame the process rendered before, not the one before.
void renderFramesAcrossProcesses(const Scene& scene, const CameraPath& path, const RenderSettings& settings,
                                 int frameCount, const ProcessGroup& group, const FrameCallback& onFrame,
                                 const std::function<bool(int frame)>& needsFilm, const PipelineCallback& onPipeline,
                                 const FrameTimeline& timeline);

}  // namespace raycache
