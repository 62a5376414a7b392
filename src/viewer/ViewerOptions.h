#pragma once
// How `raycache view` runs, besides what it renders (RenderJob).
#include <optional>
#include <string>

#include "rendercache/ReshadeBudget.h"
#include "viewer/RenderCacheDisplay.h"

namespace raycache {

struct ViewerOptions {
    // Scripted run: render this many frames of the camera path, each shown
    // once, print per-frame timings, write the screenshot if asked, exit.
    // Empty: interactive until the window closes.
    std::optional<int> scriptedFrames;
    int warmupFrames = 0;        // scripted: frames left out of the summary
    std::string screenshotPath;  // scripted: written after the last frame; interactive: what F12 writes
    bool hideUi = false;         // start with the panel hidden (the window shows the frame only)
    bool vsync = true;           // interactive only; scripted runs never wait for the display
    float movingScale = 0.5f;    // resolution factor while the camera moves
    // --pipeline auto: a full frame slower than this while the camera moves
    // does not keep the display rate (AutoPipelineRule).
    double targetFrameMs = 1000.0 / 30.0;
    bool difference = false;     // start showing the difference to the uncached image
    bool cacheLevels = false;    // start with the cube level per pixel overlay on
    std::optional<int> inspectObject;  // start with this object's cube in the inspector
    // The Render Cache pipeline at its own rate or one request per frame
    // (docs/viewer.md), and the async mode's tracer threads (0: half).
    RenderCacheDisplay renderCacheDisplay = RenderCacheDisplay::Sync;
    int renderCacheTraceThreads = 0;
    int renderCacheDisplayThreads = 0;  // 0: all
    double renderCacheRequestFrames = 2.0;  // display frames of tracing one request asks for
    double renderCacheReshadeMs = kDefaultReshadeBudgetMs;  // async reshading's budget a frame, 0: none
    int samplesPerPixel = 1;  // --spp: a still view refined to this many (RenderWorkerSetup::samplesPerPixel)
};

}  // namespace raycache
