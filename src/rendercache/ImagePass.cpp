// RenderCachePipeline's image: the samples where there are, the edge-aware
// 3x3 and 7x7 fills in the holes (rendercache/HoleFilling.h), a filled
// hole's texture at its own centre, the environment where no sample reaches.
#include <cstring>

#include "core/Elapsed.h"
#include "render/CameraRays.h"
#include "rendercache/PixelStateBits.h"
#include "rendercache/RenderCacheFrameContext.h"
#include "rendercache/RowRetexturing.h"

namespace raycache {

void RenderCachePipeline::makeImage(FrameContext& f) {
    // One pass that reads the samples' colours from the pool. (A pass of
    // its own that copied them into the film first cost a write and a read
    // of the whole film.)
    const auto start = std::chrono::steady_clock::now();
    const int width = f.width, height = f.height;
    const Camera& camera = f.camera;
    Image& film = f.film;
    std::vector<PixelState>& state = overlays_.state;
    const CameraRays rays(camera, width, height);
    // A background sample shows what it saw, like any other: looking up an
    // image environment along every pixel's ray again cost more than the
    // rest of this pass.
    const SampleColors colors{pool_.look.data(), image_.pixelIndex(0, 0), static_cast<std::size_t>(image_.stride())};
    // Edge-aware: a hole takes the samples of one surface around it.
    const SampleSurfaces surfaces{&image_, pool_.point.data(), image_.pixelIndex(0, 0),
                                  static_cast<std::size_t>(image_.stride())};
    // A hole filled from a textured surface shows that surface's texture at
    // its own centre: the lighting and rest of the group's first sample,
    // the albedo where the hole's centre ray meets that sample's primitive
    // (on a checkerboard floor the filters' mean of neighbouring squares is
    // a grey that neither square has). Where it misses, the filter's mean.
    // Done in the fill's own trip, a row as soon as a filter has filled its
    // holes, while the samples around them are still in the caches (a trip
    // of its own waited on memory for each hole's sample).
    std::vector<std::int64_t> retexturedHolesPerRow(static_cast<std::size_t>(height), 0);
    const FilledHolesVisitor retexture = [&](int y, const std::uint64_t* filledBits) {
        RowRetexturing retexturing(scene_.objects, rays, y);
        std::int64_t retexturedHoles = 0;
        forEachPixelSet(filledBits, width, [&](int x) {
            const auto i = static_cast<std::size_t>(y * width + x);
            const int source = fillSource_[i];
            const std::size_t slot = image_.pixelIndex(source % width, source / width);
            if (!pool_.look[slot].textured) return;
            ++retexturedHoles;
            const int object = pool_.point[slot].objectId;
            const auto distance = [&] {
                return length(scene_.objects[static_cast<std::size_t>(object)].origin + pool_.point[slot].position -
                              camera.position);
            };
            retexturing.color(x, object, pool_.texturing[slot], distance, film.at(x, y));
        });
        retexturedHolesPerRow[static_cast<std::size_t>(y)] += retexturedHoles;
    };
    f.filled = fillHoles(state, film, parallel_, &bytes_, &colors, &surfaces, &fillSource_,
                         f.rc.textureRefetch ? &retexture : nullptr);
    const FillCounts& filled = f.filled;
    ReconstructionCounts& touched = f.touched;
    touched.filledRefetch = f.rc.textureRefetch && filled.filled3x3 + filled.filled7x7 > 0;
    f.stats.filled3x3 = filled.filled3x3;
    f.stats.filled7x7 = filled.filled7x7;
    f.stats.unfilled = filled.unfilled;
    if (filled.unfilled > 0)
        parallel_.forEachIndex(height, [&](int y, int) {
            // There are few (a handful a frame): memchr finds them a register at a time.
            const auto* const row =
                reinterpret_cast<const unsigned char*>(state.data()) + static_cast<std::size_t>(y * width);
            const auto unfilled = static_cast<unsigned char>(PixelState::Unfilled);
            for (const void* at = std::memchr(row, unfilled, static_cast<std::size_t>(width)); at;) {
                const auto x = static_cast<int>(static_cast<const unsigned char*>(at) - row);
                film.at(x, y) = kernel_.shading().background(rays.ray(x, y));
                at = std::memchr(row + x + 1, unfilled, static_cast<std::size_t>(width - x - 1));
            }
        });
    f.stats.filterMs = millisecondsSince(start);
    touched.filled3x3 = filled.filled3x3;
    touched.filled7x7 = filled.filled7x7;
    touched.unfilled = filled.unfilled;
    touched.rowsWithHoles = filled.rowsWithHoles;
    for (std::int64_t r : retexturedHolesPerRow) touched.retexturedHoles += r;
}

}  // namespace raycache
