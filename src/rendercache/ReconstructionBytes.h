#pragma once
// The bytes a Render Cache frame's reconstruction moves, as a counted model
// (docs/render-cache.md, "What reconstruction costs"): for
// each pass, the records it reads and writes (sizeof of the real records:
// SamplePoint, SampleLook, ReshadeInputs, SampleTexturing, PointImage's
// keys, PixelState, the priority map's floats, the film's Rgb, ...) times
// how many of them this frame's counts say it touched, read + written.
//
// Counted, not measured: it is the bytes the passes' records span, not the
// traffic the memory controller sees. A record written in part counts whole
// (its cache line is read and written anyway); a row of records a pass reads
// again for neighbouring pixels (depth culling's 3x3 keys, the rows beside
// a row of holes) counts once; sparse neighbourhoods (the second chance's 8
// keys, a hole's neighbours) count per read, as the loops make them. Caches
// keep some of these bytes, and the hardware moves whole 64-byte lines, so
// real traffic can be lower (reuse) or higher (a 4-byte key read costs a
// line where samples land scattered).
#include <cstdint>

namespace raycache {

// What one frame's reconstruction passes touched, counted by the pipeline
// (rendercache/RenderCachePipeline.cpp) as they run.
struct ReconstructionCounts {
    std::int64_t width = 0, height = 0;  // the image, pixels
    std::int64_t pixelSlots = 0;         // pool slots (and PointImage keys) of the image and its margin

    // Reprojection's first round and second chance.
    std::int64_t usedSlots = 0;      // slots the first round visits: pixel slots and overflow slots in use
    std::int64_t liveSamples = 0;    // of those, holding a sample
    std::int64_t offered = 0;        // samples offered to a pixel (landed in the image or its margin)
    std::int64_t farOffers = 0;      // of those, landed too far from their band: tested on one thread
    std::int64_t secondChances = 0;  // losers of the first round, each offered a neighbour
    bool predicts = false;           // the next camera's pixel of every sample is found and kept

    // The copy of the winners to their pixels' slots.
    std::int64_t placed = 0;           // pixels holding a sample after reprojection
    std::int64_t moved = 0;            // of those, won by a second chance
    std::int64_t reshadeCopied = 0;    // winners that depend on the eye: ReshadeInputs copied
    std::int64_t texturingCopied = 0;  // textured winners: SampleTexturing copied

    // Holes, depth culling, priorities, texture re-fetch (one pass over the image).
    std::int64_t holes = 0;       // pixels without a sample, culled ones included
    bool culls = false;           // depth culling ran
    std::int64_t retextured = 0;  // textured samples re-fetched (their pixel's centre ray met, hit or miss)

    // Request maps.
    std::int64_t tiles = 0;                   // tiles of a request map
    bool requestMap = false;                  // this frame's camera's map was built
    std::int64_t requested = 0;               // pixels it asked for
    std::int64_t pixelsInRequestedTiles = 0;  // pixels of the tiles that got a ray
    bool everyPixelRequested = false;         // a frame that traces every pixel: the list, no map
    bool predictionMap = false;               // the predicted camera's map was built
    std::int64_t predictedOffered = 0;        // pixels it asked for, holes or not
    std::int64_t predictedKept = 0;           // of those, holes: the predicted requests
    std::int64_t pixelsInPredictedTiles = 0;  // pixels of its tiles that got a ray

    // Fills and the image.
    std::int64_t filled3x3 = 0, filled7x7 = 0, unfilled = 0;
    std::int64_t rowsWithHoles = 0;    // rows whose states the fills rewrite
    bool filledRefetch = false;        // filled holes were re-fetched from their surface's texture
    std::int64_t retexturedHoles = 0;  // filled holes re-fetched: their group's first sample is textured
};

// Bytes each pass moves (read + written), counted by reconstructionBytes().
struct ReconstructionBytes {
    std::int64_t firstRound = 0;   // reprojection: clearing the depth image, projection, depth test, second chance
    std::int64_t copy = 0;         // reprojection: each pixel's winner copied to its slot
    std::int64_t holes = 0;        // holes, depth culling, priorities, texture re-fetch
    std::int64_t requestMaps = 0;  // the request maps (this frame's camera and the predicted one)
    std::int64_t fills = 0;        // 3x3 and 7x7 fills, the image, re-fetch of filled holes
    std::int64_t total() const { return firstRound + copy + holes + requestMaps + fills; }
};

// The counted model of the header comment, pass by pass (the terms and why
// each count: ReconstructionBytes.cpp). Linear in the counts.
ReconstructionBytes reconstructionBytes(const ReconstructionCounts& counts);

}  // namespace raycache
