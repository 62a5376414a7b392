#pragma once
// The viewer's Dear ImGui panel: controls, live statistics, the frame-time
// graph, the difference view's figures and the cache inspector window.
// Call between ViewerWindow::beginUiFrame and endUiFrame.
#include <span>

#include "scene/Scene.h"
#include "viewer/AutoPipelineRule.h"
#include "viewer/DisplayFrame.h"
#include "viewer/FrameTimeHistory.h"
#include "viewer/ViewerUiState.h"

namespace raycache {

// UI-thread time of the last shown frame, milliseconds.
struct UiThreadTimes {
    double uploadMs = 0.0;   // texture upload of the frame (and inspector picture)
    double uiMs = 0.0;       // building and drawing the panel
    double presentMs = 0.0;  // blit + buffer swap
};

struct ViewerPanelInput {
    const Scene* scene = nullptr;
    const DisplayFrame* frame = nullptr;       // the frame on screen
    const FrameTimeHistory* intervals = nullptr;  // time between shown frames
    const FrameTimeHistory* renderTimes = nullptr;
    UiThreadTimes uiTimes;
    std::span<const int> cachedObjects;        // objects with a cube under the config in use
    unsigned int inspectorTexture = 0;         // GL texture holding the inspector picture
    int inspectorWidth = 0;
    int inspectorHeight = 0;
    const AutoPipelineRule* autoRule = nullptr;  // pipeline auto's rule (its estimates); may be null
    long long autoFullPixels = 0;                // the sizes it compared at, full frame and Render Cache
    long long autoRenderCachePixels = 0;
};

void drawViewerPanel(const ViewerPanelInput& in, ViewerUiState& state, ViewerActions& actions);

}  // namespace raycache
