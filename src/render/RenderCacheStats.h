#pragma once
// What one Render Cache frame did (FrameStats::renderCache): where its time
// went, split as the documents split it (reconstruction vs sample
// generation), and where its pixels came from.
#include <cstdint>

namespace raycache {

struct RenderCacheStats {
    // Reconstruction, wall milliseconds.
    double reprojectMs = 0.0;  // aging, eviction, projection, depth test
    double mapsMs = 0.0;       // depth culling, hole detection, priority and request maps, prediction maps
    double filterMs = 0.0;     // 3x3 filter, 7x7 prefilter, writing the image
    // Sample generation, wall milliseconds.
    double traceMs = 0.0;    // the requested pixels (this frame's camera and the predicted one)
    double reshadeMs = 0.0;  // view-dependent colour of reprojected samples shaded again

    double reconstructionMs() const { return reprojectMs + mapsMs + filterMs; }
    double sampleGenerationMs() const { return traceMs + reshadeMs; }

    std::int64_t pixels = 0;        // in the image
    std::int64_t budget = 0;        // rays the frame was allowed
    std::int64_t fresh = 0;         // pixels traced through this frame's camera
    std::int64_t predicted = 0;     // pixels traced through the predicted camera
    std::int64_t reprojected = 0;   // pixels showing a sample from an earlier frame
    std::int64_t reshaded = 0;      // of those, shaded again from the new eye
    std::int64_t culled = 0;        // samples hidden by depth culling
    std::int64_t holes = 0;         // pixels without a sample after reprojection (culled included)
    std::int64_t filled3x3 = 0;
    std::int64_t filled7x7 = 0;
    std::int64_t unfilled = 0;
    std::int64_t evicted = 0;       // samples past their maximum age
    std::int64_t lost = 0;          // samples behind a nearer one, past the margin or behind the eye
    std::int64_t liveSamples = 0;   // in the cache at the end of the frame
    bool refreshedAll = false;      // the first frame, or too many holes: every pixel was traced

    double freshShare() const { return pixels > 0 ? static_cast<double>(fresh) / static_cast<double>(pixels) : 0.0; }
};

}  // namespace raycache
