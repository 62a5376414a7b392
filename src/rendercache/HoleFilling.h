#pragma once
// Image generation of the Render Cache (Zhu, Wang and Luebke 2005; enhanced Render Cache,
// Walter et al. 2002): pixels without a sample take the weighted mean of
// the samples among their 3x3 neighbours (edge neighbours count twice,
// corners once); pixels the 3x3 filter cannot reach take the mean of the
// samples in their 7x7 box (the prefilter), applied only there, like the
// stencil-masked pass of the GPU version. Both filters can be edge-aware:
// only the samples on one surface count (rendercache/SurfaceClusters.h).
#include <cstdint>
#include <functional>
#include <vector>

#include "core/Image.h"
#include "core/Parallel.h"
#include "rendercache/PixelState.h"
#include "rendercache/PointImage.h"
#include "rendercache/SamplePool.h"

namespace raycache {

// The prefilter's box: 2 * kPrefilterRadius + 1 pixels a side.
inline constexpr int kPrefilterRadius = 3;

struct FillCounts {
    std::int64_t filled3x3 = 0;
    std::int64_t filled7x7 = 0;
    std::int64_t unfilled = 0;  // left for the caller: state Unfilled, pixel untouched
    std::int64_t rowsWithHoles = 0;  // rows whose states the fill rewrites (rendercache/ReconstructionBytes.h)
};

// Where the samples' colours are when they are not in the film yet: pixel
// (x, y)'s in looks[origin + y * stride + x] (the sample pool, whose slots
// are the pixels of the image and its margin).
struct SampleColors {
    const SampleLook* looks = nullptr;
    std::size_t origin = 0, stride = 0;
    const Rgb& at(int x, int y) const {
        return looks[origin + static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)].color;
    }
};

// What surface each pixel's sample lies on, for the edge-aware fills
// (rendercache/SurfaceClusters.h): pixel (x, y)'s depth in `depths`, its
// object in points[origin + y * stride + x] (the sample pool, as SampleColors).
struct SampleSurfaces {
    const PointImage* depths = nullptr;
    const SamplePoint* points = nullptr;
    std::size_t origin = 0, stride = 0;
    float depth(int x, int y) const { return depths->depthAt(x, y); }
    int object(int x, int y) const {
        return points[origin + static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)].objectId;
    }
};

// The pixels where showsSample(state) show their samples' colours: taken
// from `samples` and written to `film` in the same pass as the 3x3 filter
// when `samples` is given, else already in `film`. The holes (isHole) are
// filled from those pixels only, and their state set to Filled3x3,
// Filled7x7 or Unfilled. With `surfaces`, each filter takes the mean of
// one group of the samples it reaches, those on one surface
// (SurfaceClusters); without, of all of them. With `surfaces` and
// `fillSource` (resized to the image's pixels), each filled hole's entry
// gets the pixel (y * width + x) of the first sample of the group it took
// (the caller may shade the hole from that sample's surface); other
// entries are not written.
// `scratch`, when given, is reused from frame to frame (no allocation).
// `onFilled`, when given, is called once for each row in which the filters
// filled holes, with those holes as bits (rendercache/PixelStateBits.h's
// layout), on the worker that filled them, right after: the samples around
// them are then still in its caches. It may change the colours of those
// holes only (other rows are being filled meanwhile).
using FilledHolesVisitor = std::function<void(int y, const std::uint64_t* filled)>;
FillCounts fillHoles(std::vector<PixelState>& state, Image& film, const Parallel& parallel,
                     std::vector<unsigned char>* scratch = nullptr, const SampleColors* samples = nullptr,
                     const SampleSurfaces* surfaces = nullptr, std::vector<std::int32_t>* fillSource = nullptr,
                     const FilledHolesVisitor* onFilled = nullptr);

}  // namespace raycache
