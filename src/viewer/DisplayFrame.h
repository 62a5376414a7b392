#pragma once
// One rendered frame on its way from the render thread to the screen, with
// everything the panel shows about it. Its buffers are reused frame after
// frame (see FrameHandoff).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "render/CacheLevelImage.h"
#include "render/FrameStats.h"
#include "scene/Camera.h"
#include "viewer/AutoPipelineRule.h"

namespace raycache {

struct DisplayFrame {
    std::uint64_t serial = 0;        // 1, 2, ... in render order; 0 = no frame yet
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // what to show, 8-bit sRGB RGBA, row 0 at the top
    Camera camera;                   // the camera it was rendered with
    int pathFrame = -1;              // frame of the camera path, or -1 for the interactive camera
    bool reducedResolution = false;  // rendered smaller while the camera moves
    FrameStats stats;
    // Which way made the frame: a full frame or the Render Cache. Under
    // pipeline auto the Render Cache asked for shows a full frame until its
    // samples of the whole image have come (`renderCachePriming`).
    bool autoPipeline = false;
    ShownPipeline shown = ShownPipeline::FullFrame;
    bool renderCachePriming = false;
    std::size_t cacheBytes = 0;      // memory of all caching cubes
    // --spp N on a still view (viewer/ProgressiveFilm.h): the sample layers
    // the shown image holds, of `refinementTarget` (0 when not refining; 0
    // layers: the plain frame). `refinementReused`: the refinement was
    // complete, nothing was rendered and `stats` are the last layer's.
    int refinedSamples = 0;
    int refinementTarget = 0;
    bool refinementReused = false;

    // Time on the render thread, milliseconds.
    double renderMs = 0.0;      // the ray traced frame
    double encodeMs = 0.0;      // film -> 8-bit sRGB, inspector picture
    double differenceMs = 0.0;  // the uncached render and heat map (difference view only)

    // Difference view: rgba holds the heat map against the uncached render.
    bool showsDifference = false;
    double meanDifference = 0.0;  // mean absolute difference of the displayed channels, [0, 1]

    // Cache inspector: the inspected object's cube unfolded (see CubeInspectorImage).
    int inspectedObject = -1;  // -1: none (rgba below is empty)
    int inspectorWidth = 0;
    int inspectorHeight = 0;
    std::vector<std::uint8_t> inspectorRgba;
    double inspectedInvalidPercent = 0.0;  // after this frame
    std::int64_t inspectedDroppedTexels = 0;  // dropped by the last scene change (animated scenes)

    // Cube level per pixel: rgba has the record blended in
    // (CacheLevelOverlayImage), and how many pixels hold each value.
    bool showsCacheLevels = false;
    CacheLevelImage::Counts cacheLevelPixels{};

    // The Render Cache displayed at its own rate (RenderCacheDisplay::Async;
    // rendercache/AsyncRenderCache.h): rates over the last second.
    bool asyncRenderCache = false;
    int displayThreads = 0, traceThreads = 0;
    double displayFps = 0.0;          // display frames reconstructed per second
    double samplesPerSecond = 0.0;    // new samples (camera rays) the tracer traced per second
    double batchesPerSecond = 0.0;    // batches it handed over per second
    double requestsPerSecond = 0.0;   // request maps it traced to their end per second
    double traceBusyShare = 0.0;      // share of the time the tracer was tracing
    std::int64_t mergedSamples = 0;   // samples this frame merged into the pool
    int reshadeInterval = 1;          // this frame reshaded one in this many view-dependent samples

    std::string configError;  // why the last requested settings were rejected; empty if they were used
};

}  // namespace raycache
