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

    // Bytes reconstruction's passes move, read + written: counted from the
    // record sizes and this frame's counts (rendercache/ReconstructionBytes.h),
    // not measured memory traffic.
    std::int64_t firstRoundBytes = 0;  // reprojection: clearing the depth image, projection, depth test, second chance
    std::int64_t copyBytes = 0;        // reprojection: the winners copied to their pixels' slots
    std::int64_t holesBytes = 0;       // holes, depth culling, priorities, texture re-fetch
    std::int64_t requestMapBytes = 0;  // request maps, this frame's camera and the predicted one
    std::int64_t fillBytes = 0;        // fills, the image, re-fetch of filled holes

    // The counted bytes of each timed step, and of reconstruction.
    std::int64_t reprojectBytes() const { return firstRoundBytes + copyBytes; }
    std::int64_t mapsBytes() const { return holesBytes + requestMapBytes; }
    std::int64_t filterBytes() const { return fillBytes; }
    std::int64_t reconstructionBytes() const { return reprojectBytes() + mapsBytes() + filterBytes(); }
    // Counted bytes over wall time, GB/s (10^9 bytes a second); 0 when the
    // time is not positive.
    static double gigabytesPerSecond(std::int64_t bytes, double ms) {
        return ms > 0.0 ? static_cast<double>(bytes) / (ms * 1e6) : 0.0;
    }
    double reconstructionGbPerSecond() const { return gigabytesPerSecond(reconstructionBytes(), reconstructionMs()); }
    double reprojectGbPerSecond() const { return gigabytesPerSecond(reprojectBytes(), reprojectMs); }
    double mapsGbPerSecond() const { return gigabytesPerSecond(mapsBytes(), mapsMs); }
    double filterGbPerSecond() const { return gigabytesPerSecond(filterBytes(), filterMs); }

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
