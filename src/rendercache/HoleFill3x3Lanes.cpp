#include "rendercache/HoleFill3x3Lanes.h"

#include "core/FloatLanes.h"
#include "core/LaneLevels.h"
#include "rendercache/SurfaceClusters.h"

namespace raycache {

#define RAYCACHE_LANE_KERNELS "rendercache/HoleFill3x3LaneKernels.inc"
#include "core/LaneLevelsInclude.h"

namespace {

// Room for pixel x at x + 1, the pixels either side, and a whole register
// of sixteen lanes read from the last pixel.
std::size_t paddedLength(int width) {
    return (static_cast<std::size_t>(width) + 2 + kFloatLanes + 15) / 16 * 16;
}

// Each vector `length` long.
template <class... Vectors>
void resizeEach(std::size_t length, Vectors&... vectors) {
    (vectors.resize(length), ...);
}

}  // namespace

void FillRow::resize(int width) { resizeEach(paddedLength(width), sample, red, green, blue, depth, object); }

void Fill3x3Results::resize(int width) { resizeEach(paddedLength(width), red, green, blue, info); }

void buildFillRow(const FillRowSource& source, int width, FillRow& row) {
    row.resize(width);
    RAYCACHE_LANE_DISPATCH(buildFillRowLanes, source, width, row);
}

void fill3x3Row(const FillRow& above, const FillRow& row, const FillRow& below, const std::uint64_t* holeBits,
                int width, Fill3x3Results& results) {
    results.resize(width);
    RAYCACHE_LANE_DISPATCH(fill3x3RowLanes, above, row, below, holeBits, width, results);
}

void composeFilmRow(const FillRow& row, const Fill3x3Results& results, bool samplesFromRow, int width, Rgb* film) {
    RAYCACHE_LANE_DISPATCH(composeFilmRowLanes, row, results, samplesFromRow, width, film);
}

}  // namespace raycache
