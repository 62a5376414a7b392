#pragma once
// Options of the Render Cache pipeline (Walter et al. 1999; Zhu, Wang and Luebke 2005; `--pipeline render-cache`):
// how many rays a frame may trace, how requests are spread, how long a
// reprojected sample lives, and whether view-dependent colour is shaded
// again from the new eye. Plain data; validateRenderCacheSettings() checks it.
#include <array>
#include <cstdint>

#include "scene/ReprojectedReflections.h"

namespace raycache {

struct RenderCacheSettings {
    // Mix of the request map: weight of a screen tile = (1 - alpha) * uniform
    // + alpha * its share of the priority (holes and old samples).
    float alpha = 0.25f;
    // Primary rays a frame may trace, as a share of the image's pixels.
    float budget = 0.05f;
    // When > 0, the budget is chosen each frame to hold this frame time
    // (milliseconds): images then depend on the machine's speed.
    float targetFrameMs = 0.0f;
    // A sample is evicted once it has been reprojected this many times.
    int maxAge = 32;
    // Share of the budget spent on pixels where holes will open in the next
    // frame, traced through the camera predicted from the last two frames.
    float predictShare = 0.2f;
    // Samples are kept this far past each image edge (share of the side).
    float margin = 0.05f;
    // Enhanced Render Cache depth culling: a point is hidden when more of its
    // 3x3 neighbours are nearer than it by this share of its depth than not.
    float depthCullThreshold = 0.1f;
    // Side of the screen tiles of hole detection and the request map, pixels.
    int requestTileSize = 8;
    // More than this share of the image in holes (a cut, the first frame):
    // every pixel is traced.
    float refreshAllHoleShare = 0.5f;
    ReprojectedReflections reflections = ReprojectedReflections::Reshade;
    // With reflections reshaded: a frame whose camera moved reshades one in
    // this many of the reprojected view-dependent samples (a fixed pattern
    // that shifts every frame, so each is reshaded once in this many moving
    // frames); the others keep the colour of an older eye until their turn,
    // and the first still frame reshades them all. 1 (the default) reshades
    // every one every frame; larger values bound reshading's share of a
    // display frame (rendercache/ReshadeSelection.h).
    int reshadeInterval = 1;
    // A textured sample shows the albedo its pixel's centre sees on its
    // primitive, multiplied by its stored lighting (rendercache/SampleRetexturing.h);
    // off, the colour it was traced with (as the 2002 Render Cache).
    bool textureRefetch = true;
    std::uint64_t seed = 1;
};

// The largest RenderCacheSettings::reshadeInterval: a reflection older than
// this many moving frames shows plainly at the camera speeds of the viewer.
inline constexpr int kMaxReshadeInterval = 16;

// Throws InputError naming the option (as `--rc-...`) when a value is out of
// range: alpha outside [0, 1], budget outside (0, 1], negative target, ...
void validateRenderCacheSettings(const RenderCacheSettings& settings);

// RenderCacheSettings::textureRefetch's two values, in the order messages
// list them, under their `--rc-texture` names: "refetch" (true), "reproject".
inline constexpr std::array kTextureRefetchValues{true, false};
const char* textureRefetchName(bool textureRefetch);

}  // namespace raycache
