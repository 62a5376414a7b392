#pragma once
// Everything the panel edits, and the one-off actions it asks for. Plain
// data owned by the Viewer.
#include <cstdint>

#include "viewer/ViewerRenderConfig.h"

namespace raycache {

struct ViewerUiState {
    ViewerRenderConfig config;   // what the panel shows and edits
    float resolutionScale = 1.0f;
    float movingScale = 0.5f;    // extra factor while the camera moves
    bool continuous = true;
    bool playPath = false;
    bool playAnimation = true;   // animated scenes: the clock runs
    float animationTime = 0.0f;  // seconds of the animation shown
    float animationSpeed = 1.0f;
    bool difference = false;
    float differenceGain = 1.0f;
    int renderCacheOverlay = 0;  // RenderCacheOverlay
    bool renderCacheAsync = false;  // the Render Cache at its own rate (--render-cache-display)
    bool cacheLevels = false;    // the cube level per pixel overlay
    int inspectObject = -1;
    int inspectorFaceSize = 128;
    bool showUi = true;
    bool showInspector = false;
};

struct ViewerActions {
    bool resetCamera = false;
    bool restartPath = false;
    bool clearCaches = false;
    bool screenshot = false;
    bool quit = false;
};

}  // namespace raycache
