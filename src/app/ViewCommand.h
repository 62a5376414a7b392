#pragma once
// `raycache view`: walk through a scene in a window, or (--frames) play its
// camera path in the window, print per-frame timings, write a screenshot and exit.
#include <iosfwd>
#include <optional>
#include <string>

#include "session/RenderJob.h"
#include "viewer/PipelineChoice.h"
#include "rendercache/ReshadeBudget.h"
#include "viewer/RenderCacheDisplay.h"

namespace raycache {

struct ViewCommandOptions {
    RenderJobOptions job;        // scene, window/film size, path, threads, depth, caching
    // --pipeline (the view command's own: it adds auto, and is the panel's
    // starting value; a scene file's "pipeline" key is for `render`).
    ViewerPipeline pipeline = ViewerPipeline::Auto;
    double targetFps = 30.0;     // --target-fps: the display rate auto's full frames must keep
    std::string screenshotPath;  // --screenshot (.png/.exr)
    bool hideUi = false;         // --hide-ui
    int warmupFrames = 0;        // --warmup (scripted runs)
    bool noVsync = false;        // --no-vsync
    float movingScale = 0.5f;    // --moving-scale
    bool difference = false;     // --difference
    bool levelOverlay = false;   // --level-overlay
    std::string inspectObject;   // --inspect: object name
    // --render-cache-display; empty: async when interactive, sync for --frames.
    std::optional<RenderCacheDisplay> renderCacheDisplay;
    int renderCacheTraceThreads = 0;    // --render-cache-trace-threads, 0 = half of --threads
    int renderCacheDisplayThreads = 0;  // --render-cache-display-threads, 0 = --threads
    double renderCacheRequestFrames = 2.0;  // --render-cache-request-frames
    double renderCacheReshadeMs = kDefaultReshadeBudgetMs;  // --render-cache-reshade-ms
};

// Checks every option (InputError) before opening a window, then runs the
// viewer: interactive without --frames, scripted with it. Throws
// RuntimeError when no window can be opened (no display) or rendering fails.
// What loading the scene repaired goes to `notes`, one "note: …" line each.
void runViewCommand(const ViewCommandOptions& options, std::ostream& out, std::ostream& notes);

}  // namespace raycache
