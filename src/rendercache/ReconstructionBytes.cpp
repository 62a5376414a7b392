#include "rendercache/ReconstructionBytes.h"

#include "core/Rgb.h"
#include "render/CameraRays.h"
#include "rendercache/PixelState.h"
#include "rendercache/PointImage.h"
#include "rendercache/Reprojection.h"
#include "rendercache/RequestMap.h"
#include "rendercache/SamplePool.h"

namespace raycache {

namespace {

// The records, by the types the passes use.
constexpr std::int64_t kPoint = sizeof(SamplePoint);
constexpr std::int64_t kLook = sizeof(SampleLook);
constexpr std::int64_t kReshade = sizeof(ReshadeInputs);
constexpr std::int64_t kTexturing = sizeof(SampleTexturing);
constexpr std::int64_t kKey = sizeof(PointImage::emptyKey());  // a depth-image pixel
constexpr std::int64_t kWinner = sizeof(decltype(ReprojectionScratch::winner)::value_type);
constexpr std::int64_t kNextPixel = sizeof(decltype(ReprojectionScratch::nextPixel)::value_type);
constexpr std::int64_t kLanded = sizeof(ReprojectionScratch::Landed);
constexpr std::int64_t kState = sizeof(PixelState);
constexpr std::int64_t kPriority = sizeof(float);  // buildRequestMap's priority map
// The per-pixel scratch bytes: culling's flags, the fills' outcomes, prediction's coverage.
constexpr std::int64_t kFlag = sizeof(unsigned char);
constexpr std::int64_t kTilePriority = sizeof(decltype(RequestMap::tilePriority)::value_type);
constexpr std::int64_t kTileRequests = sizeof(decltype(RequestMap::tileRequests)::value_type);
constexpr std::int64_t kRequest = sizeof(PixelCoord);
constexpr std::int64_t kFilm = sizeof(Rgb);
constexpr std::int64_t kFillSource = sizeof(std::int32_t);  // fillHoles()'s fillSource

// One buildRequestMap() call over `pixels` priorities and `tiles` tiles that
// asked for `requested` pixels from tiles holding `pixelsInRequestedTiles`.
std::int64_t requestMapBytes(std::int64_t pixels, std::int64_t tiles, std::int64_t pixelsInRequestedTiles,
                             std::int64_t requested) {
    std::int64_t bytes = pixels * kPriority;               // the tile sums read every priority
    bytes += tiles * 2 * (kTilePriority + kTileRequests);  // each tile's sum and rays, written and read
    bytes += pixelsInRequestedTiles * kPriority;           // read again where a tile got rays: its levels
    bytes += requested * kRequest;                         // the requested pixels written
    return bytes;
}

constexpr std::int64_t kNeighbours = 8;  // pixels around a pixel

}  // namespace

ReconstructionBytes reconstructionBytes(const ReconstructionCounts& c) {
    const std::int64_t pixels = c.width * c.height;
    ReconstructionBytes b;

    // First round (Reprojection.cpp): the depth image cleared, every used
    // slot's point projected, every live sample's look read for its age, then
    // the depth test on the keys and the second chance for the losers.
    std::int64_t& first = b.firstRound;
    first += c.pixelSlots * kKey;                       // PointImage::reset writes every key
    first += c.usedSlots * kPoint;                      // points read sixteen slots at a time, empty ones too
    first += c.liveSamples * kLook;                     // a live sample's age (an empty slot's look is not read)
    if (c.predicts) first += c.usedSlots * kNextPixel;  // the next camera's pixel, written for every slot
    first += c.offered * kKey;                          // each offer reads its pixel's key
    first += (c.placed - c.moved) * (kKey + kWinner);   // a first-round winner's key and slot written (a winner
                                                        // pushed out later wrote them too: not counted)
    first += c.farOffers * 2 * kLanded;                 // listed, then read back on one thread
    first += c.secondChances * 2 * kLanded;             // each loser listed, then read back
    first += c.secondChances * kNeighbours * kKey;      // its neighbours' keys read
    first += c.moved * (kKey + kWinner);                // a neighbour won: key and slot written

    // Copy (Reprojection.cpp): every pixel slot's key read; an empty pixel's
    // slot marked empty (its point's object written: the record counts
    // whole); a winner's point and look read from its source slot and
    // written to the pixel's, with the records only some samples have; the
    // next camera's pixel follows its sample.
    std::int64_t& copy = b.copy;
    copy += c.pixelSlots * kKey;                            // every pixel's key
    copy += (c.pixelSlots - c.placed) * kPoint;             // empty slots marked
    copy += c.placed * (kWinner + 2 * kPoint + 2 * kLook);  // the winner's source slot read, its point and look moved
    copy += c.moved * kKey;                                 // the second chance's mark cleared
    copy += c.reshadeCopied * 2 * kReshade;                 // samples that depend on the eye
    copy += c.texturingCopied * 2 * kTexturing;             // textured samples
    if (c.predicts) copy += (c.pixelSlots + c.placed) * kNextPixel;  // written per pixel slot, read per winner

    // Holes, culling, priorities, re-fetch (RenderCachePipeline.cpp, one
    // pass over the image's rows): each pixel's key read (culling's rows
    // above and below are the neighbouring rows' own: once), the culling
    // flags written then read, the state and priority written; a pixel with
    // a sample reads its look; a re-fetched textured sample reads its point
    // and colour's parts and writes its colour back (only where its centre
    // ray meets its primitive: counted for each).
    std::int64_t& holes = b.holes;
    holes += pixels * kKey;                                 // keys
    if (c.culls) holes += pixels * 2 * kFlag;               // hidden flags, written and read
    holes += pixels * (kState + kPriority);                 // state and priority written
    holes += (pixels - c.holes) * kLook;                    // a sample's age and texture flag
    holes += c.retextured * (kPoint + kTexturing + kLook);  // re-fetched: point, parts read, colour written

    // Request maps (RenderCachePipeline.cpp, RequestMap.cpp): this frame's
    // camera's map, or the list of every pixel; then the predicted camera's:
    // the coverage flags cleared, every slot's pixel through the next camera
    // read and flagged, the priorities made from the flags, its map, and the
    // requests that are not holes erased.
    std::int64_t& maps = b.requestMaps;
    if (c.requestMap) maps += requestMapBytes(pixels, c.tiles, c.pixelsInRequestedTiles, c.requested);
    if (c.everyPixelRequested) maps += pixels * kRequest;
    if (c.predictionMap) {
        maps += pixels * kFlag;                // coverage cleared
        maps += c.pixelSlots * kNextPixel;     // every slot's next pixel read (and flagged)
        maps += pixels * (kFlag + kPriority);  // coverage read, priority written
        maps += requestMapBytes(pixels, c.tiles, c.pixelsInPredictedTiles, c.predictedOffered);
        maps += c.predictedOffered * (kRequest + kFlag);  // the erase reads each request and its flag
        maps += c.predictedKept * kRequest;               // and writes the kept ones
    }

    // Fills and the image (HoleFilling.cpp, then the pipeline's re-fetch of
    // filled holes and the background of unfilled ones). Every pixel shows a
    // sample (copied from the pool to the film) or is a hole that ends
    // filled 3x3, filled 7x7 or unfilled.
    const std::int64_t wants7x7 = c.filled7x7 + c.unfilled;
    std::int64_t& fills = b.fills;
    fills += pixels * kFlag;   // the outcomes cleared
    fills += pixels * kState;  // the holes found as bits
    // Every pixel's colour from the pool, and the film written whole
    // (samples' colours, one-surface means); for the rows with holes the
    // filters' rows (HoleFill3x3Lanes.h's FillRow) also read state, depth
    // and object (the rows beside, which both filters' boxes read: once).
    fills += pixels * (kLook + kFilm);
    fills += c.rowsWithHoles * c.width * (kState + kKey + kPoint);
    fills += c.filled3x3 * (kFillSource + kFlag);               // the 3x3 hole's source, its outcome
    fills += wants7x7 * kFlag;                                  // the 7x7 outcome
    fills += c.filled7x7 * (kFilm + kFillSource);               // the 7x7 mean and its source
    fills += c.rowsWithHoles * c.width * (2 * kState + kFlag);  // a row of holes: states rewritten
    if (c.filledRefetch) {
        fills += (c.filled3x3 + c.filled7x7) * (kFillSource + kLook);  // each one's source and its texture flag
        fills += c.retexturedHoles * (kPoint + kTexturing + kFilm);    // re-fetched (film written where met)
    }
    if (c.unfilled > 0) fills += pixels * kState + c.unfilled * kFilm;  // found by memchr, background written
    return b;
}

}  // namespace raycache
