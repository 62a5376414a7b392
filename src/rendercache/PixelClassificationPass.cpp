// RenderCachePipeline's second pass, one trip over the image: each pixel a
// hole, a culled sample (depth culling) or a reprojected sample; its
// priority for the request map; a textured sample's albedo fetched again
// where the pixel's centre meets its primitive (SampleRetexturing).
#include <algorithm>

#include "core/Elapsed.h"
#include "render/CameraRays.h"
#include "rendercache/DepthCulling.h"
#include "rendercache/PixelStateBits.h"
#include "rendercache/RenderCacheFrameContext.h"
#include "rendercache/RowRetexturing.h"
#include "rendercache/SampleRetexturing.h"

namespace raycache {

void RenderCachePipeline::classifyPixels(FrameContext& f) {
    const auto start = std::chrono::steady_clock::now();
    const RenderCacheSettings& rc = f.rc;
    const int width = f.width, height = f.height;
    const Camera& camera = f.camera;
    std::vector<PixelState>& state = overlays_.state;
    state.resize(static_cast<std::size_t>(f.pixels));
    std::vector<float>& priority = priority_;
    priority.resize(static_cast<std::size_t>(f.pixels));  // every pixel written below
    // One pass: holes, depth culling (a still camera puts every sample back
    // where it was traced: nothing to cull) and priorities. Counts per row
    // go to locals, written once (no false sharing).
    const bool cull = f.moved && rc.depthCullThreshold > 0.0f;
    std::vector<std::int64_t> holesPerRow(static_cast<std::size_t>(height), 0);
    std::vector<std::int64_t> culledPerRow(static_cast<std::size_t>(height), 0);
    std::vector<std::int64_t> reprojectedPerRow(static_cast<std::size_t>(height), 0);
    std::vector<std::int64_t> texturedPerRow(static_cast<std::size_t>(height), 0);
    const float agePriority = 0.5f / static_cast<float>(rc.maxAge);
    // Textured samples show the albedo their pixel's centre sees
    // (SampleRetexturing); a still camera puts every sample back where it was
    // traced, so they already do.
    const bool retexture = f.moved && rc.textureRefetch;
    const CameraRays centreRays(camera, width, height);
    // Each row's culling decisions, taken before the row is classified.
    std::vector<unsigned char>& hiddenPerPixel = bytes_;
    if (cull) hiddenPerPixel.resize(static_cast<std::size_t>(f.pixels));
    reshadeRowStart_.assign(static_cast<std::size_t>(height) + 1, 0);
    // The samples reshading will take, and the mark of those it leaves
    // shaded from an older eye (rendercache/ReshadeSelection.h), decided here,
    // where each look is read anyway.
    const bool reshades = f.reshading.any() && rc.reflections == ReprojectedReflections::Reshade;
    const std::size_t words = pixelStateWords(width);
    if (reshades) reshadeBits_.resize(words * static_cast<std::size_t>(height));
    parallel_.forEachIndex(height, [&](int y, int) {
        std::int64_t rowHoles = 0, rowCulled = 0, rowReprojected = 0, rowTextured = 0;
        std::size_t rowViewDependent = 0;
        // Addresses and sizes in locals (through the members the compiler
        // reloaded them after every store).
        const auto stride = static_cast<std::size_t>(image_.stride());
        const std::size_t rowSlot = image_.pixelIndex(0, y);
        const std::uint32_t* const keys = image_.keyData() + rowSlot;
        SampleLook* const looks = pool_.look.data() + rowSlot;
        const SamplePoint* const points = pool_.point.data() + rowSlot;
        const SampleTexturing* const texturings = pool_.texturing.data() + rowSlot;
        PixelState* const rowState = state.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
        float* const rowPriority = priority.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
        unsigned char* const hidden =
            cull ? hiddenPerPixel.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) : nullptr;
        if (cull) hiddenByNearerKeysRow(keys - stride, keys, keys + stride, width, rc.depthCullThreshold, hidden);
        // The frame's flags in locals too: captured by reference, each was
        // loaded through the closure for every pixel.
        const bool culling = cull, refetching = retexture;
        const float ageShare = agePriority;
        const int columns = width;
        const ReshadeSelection reshading = f.reshading;
        const bool selecting = reshades, marksOlderEye = reshades && reshading.moved;
        std::uint64_t* const chosenBits =
            selecting ? reshadeBits_.data() + static_cast<std::size_t>(y) * words : nullptr;
        if (selecting) std::fill(chosenBits, chosenBits + words, 0);
        RowRetexturing retexturing(scene_.objects, centreRays, y);
        for (int x = 0; x < columns; ++x) {
            const auto i = static_cast<std::size_t>(x);
            if (keys[x] == PointImage::emptyKey()) {
                rowState[i] = PixelState::Hole;
                rowPriority[i] = 1.0f;
                ++rowHoles;
            } else if (culling && hidden[x]) {
                rowState[i] = PixelState::Culled;
                rowPriority[i] = 1.0f;
                ++rowCulled;
            } else {
                rowState[i] = PixelState::Reprojected;
                SampleLook& look = looks[i];
                rowPriority[i] = ageShare * static_cast<float>(look.age);
                // Re-fetched below when the frame re-fetches; added without a
                // branch (a counter inside the re-fetch's branch cost this
                // pass measurably more instructions).
                rowTextured += look.textured ? 1 : 0;
                const bool chosen = reshading.chooses(look, x, y);
                rowViewDependent += chosen ? 1 : 0;
                if (selecting) chosenBits[x / 64] |= static_cast<std::uint64_t>(chosen) << (x % 64);
                // Out of its turn, a view-dependent sample keeps the colour
                // of an older eye, marked so that a still frame reshades it.
                if (marksOlderEye && !chosen && look.viewDependent != 0) look.viewDependent |= kShadedFromAnOlderEye;
                if (refetching && look.textured) {
                    const int object = points[i].objectId;
                    const auto distance = [&] {
                        return length(scene_.objects[static_cast<std::size_t>(object)].origin + points[i].position -
                                      camera.position);
                    };
                    // Where the centre misses the sample's primitive (its
                    // edge, a silhouette), the stored colour, and a ray sooner.
                    if (!retexturing.color(x, object, texturings[i], distance, look.color))
                        rowPriority[i] = std::max(rowPriority[i], kMissedPrimitivePriority);
                }
                ++rowReprojected;
            }
        }
        reprojectedPerRow[static_cast<std::size_t>(y)] = rowReprojected;
        holesPerRow[static_cast<std::size_t>(y)] = rowHoles + rowCulled;
        culledPerRow[static_cast<std::size_t>(y)] = rowCulled;
        texturedPerRow[static_cast<std::size_t>(y)] = rowTextured;
        reshadeRowStart_[static_cast<std::size_t>(y) + 1] = rowViewDependent;
    });
    for (std::int64_t c : culledPerRow) f.stats.culled += c;
    for (std::int64_t r : reprojectedPerRow) f.stats.reprojected += r;
    std::int64_t holes = 0;
    for (std::int64_t h : holesPerRow) holes += h;
    f.holes = holes;
    f.stats.holes = holes;
    f.touched.holes = holes;
    f.touched.culls = cull;
    if (retexture)
        for (std::int64_t r : texturedPerRow) f.touched.retextured += r;
    f.stats.mapsMs = millisecondsSince(start);
}

}  // namespace raycache
