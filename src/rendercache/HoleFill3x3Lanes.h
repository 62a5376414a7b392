#pragma once
// The Render Cache's 3x3 hole filter (rendercache/HoleFilling.h) a register
// of pixels at a time, for the common hole: one whose neighbouring samples
// all lie on one surface. The filter reads a row's samples through three
// rows of structure-of-arrays (FillRow): each hole's eight neighbours are
// then eight unaligned loads per field, where the per-hole code gathered
// them one by one, a branch per neighbour. A hole whose samples lie on two
// or more surfaces is left to the scalar rule
// (SurfaceClusters), which chooses among the groups.
#include <cstdint>
#include <vector>

#include "core/Rgb.h"
#include "rendercache/PixelState.h"
#include "rendercache/SamplePool.h"

namespace raycache {

// One image row as the filter reads it: pixel x at index x + 1, so that
// x - 1 and x + 1 are in range for every pixel; past both ends (and in a
// row outside the image) no sample. Arrays are padded to whole registers.
struct FillRow {
    std::vector<std::int32_t> sample;  // -1 where the pixel shows a sample (showsSample), else 0
    std::vector<float> red, green, blue;
    std::vector<float> depth;          // the sample's depth (0 when the fill is not edge-aware)
    std::vector<std::int32_t> object;  // the sample's object (0 when the fill is not edge-aware)
    int row = -1 << 30;                // the image row it holds (none yet)

    // Sizes the arrays for rows `width` pixels wide.
    void resize(int width);
};

// Where a row's fields come from: `states` null for a row outside the
// image; colours from `looks` when given, else from `film`; `keys` and
// `points` only for the edge-aware fill (null otherwise).
struct FillRowSource {
    const PixelState* states = nullptr;
    const SampleLook* looks = nullptr;
    const Rgb* film = nullptr;
    const std::uint32_t* keys = nullptr;
    const SamplePoint* points = nullptr;
};

// Fills `row` (resized for `width`) from `source`.
void buildFillRow(const FillRowSource& source, int width, FillRow& row);

// What the filter decided for each pixel of a row (only meaningful at holes).
enum class Fill3x3Outcome : std::int32_t {
    OneSurface = 1,      // all neighbouring samples on one surface: colour and source below
    NoSample = 2,        // no neighbouring sample: the 7x7 prefilter's turn
    SeveralSurfaces = 3  // the scalar rule must choose among the groups
};
// The neighbours in the order the scalar rule adds them (row above, own
// row, row below; left to right), with their filter weights.
struct Fill3x3Neighbour {
    int row, dx;
    float weight;
};
inline constexpr Fill3x3Neighbour kFill3x3Neighbours[8] = {{0, -1, 1.0f}, {0, 0, 2.0f},  {0, 1, 1.0f}, {1, -1, 2.0f},
                                                           {1, 1, 2.0f},  {2, -1, 1.0f}, {2, 0, 2.0f}, {2, 1, 1.0f}};

struct Fill3x3Results {
    std::vector<float> red, green, blue;  // the weighted mean (OneSurface)
    // 0 where the pixel is no hole; else Fill3x3Outcome in bits 0-1; the first neighbour's index into
    // kFill3x3Neighbours (the group's first sample) in bits 2-4.
    std::vector<std::int32_t> info;

    void resize(int width);
    static Fill3x3Outcome outcome(std::int32_t info) { return static_cast<Fill3x3Outcome>(info & 3); }
    static int firstNeighbour(std::int32_t info) { return (info >> 2) & 7; }
};

// The 3x3 filter at every pixel of a row whose bit is set in `holeBits`
// (rendercache/PixelStateBits.h's layout), from the rows above, of and
// below it. Bit for bit the scalar rule's mean where the outcome is
// OneSurface: the same products and sums in the same order, lane by lane.
void fill3x3Row(const FillRow& above, const FillRow& row, const FillRow& below, const std::uint64_t* holeBits,
                int width, Fill3x3Results& results);

// Row `row`'s film: each sample's colour from `row` where `samplesFromRow`
// (else the film holds them already), each hole whose outcome is
// OneSurface the mean in `results`; other pixels untouched. A register of
// pixels at a time, without a branch per run of samples.
void composeFilmRow(const FillRow& row, const Fill3x3Results& results, bool samplesFromRow, int width, Rgb* film);

}  // namespace raycache
