#pragma once
// What the UI thread asks the render thread to draw next. The newest
// request wins; counters (not flags) carry one-off actions so none is lost
// when requests replace each other.
#include <cstdint>

#include "scene/Camera.h"
#include "viewer/ViewerRenderConfig.h"

namespace raycache {

struct RenderRequest {
    Camera camera;           // ignored while playing the camera path
    int width = 1;           // film size for this frame
    int height = 1;
    bool reducedResolution = false;  // the size is lowered because the camera moves
    ViewerRenderConfig config;
    std::uint64_t clearCount = 0;        // a change clears every cache
    bool playPath = false;               // take cameras from the path, one path frame per render
    float time = 0.0f;                   // animated scenes: the moment to show (scripted runs: from the path frame)
    std::uint64_t pathRestartCount = 0;  // a change restarts the path at frame 0
    bool continuous = true;              // keep rendering when nothing changes (caches keep filling)
    bool difference = false;             // show the heat map against the uncached render
    float differenceGain = 1.0f;
    int renderCacheOverlay = 0;          // RenderCacheOverlay: what to paint over a Render Cache frame
    bool renderCacheAsync = false;       // the Render Cache at its own rate (still scenes; docs/viewer.md)
    // Pipeline auto (kAutoPipelineChoice): show the Render Cache for this
    // frame rather than a full frame (the UI thread's AutoPipelineRule decides).
    bool showRenderCache = false;
    bool cacheLevels = false;            // paint the cube level that answered each pixel (ray and hybrid pipelines)
    int inspectObject = -1;              // object whose cube to unfold, -1 = none
    int inspectorFaceSize = 128;

    bool operator==(const RenderRequest&) const = default;
};

}  // namespace raycache
