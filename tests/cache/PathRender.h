#pragma once
// Test helper: render a built-in scene's camera path with caching and keep
// every frame, its stats, and the cubes' contents afterwards.
#include <cstdint>
#include <string>
#include <vector>

#include "core/Image.h"
#include "core/ProcessGroup.h"
#include "cache/CdctSearch.h"
#include "cache/RayCache.h"
#include "render/FrameStats.h"
#include "render/TileAssignment.h"
#include "scene/Material.h"
#include "scene/Scene.h"

namespace raycache {

struct PathRender {
    std::vector<Image> frames;
    std::vector<FrameStats> stats;
    // Per caching object: its color words, then (CDCT cubes only) its depth
    // words, then (multi-resolution CCT cubes) each coarser level's words.
    std::vector<std::vector<std::uint32_t>> texels;
};

// `frames` frames of the scene's own camera path, or of its first camera when
// `still`; `technique` and `cacheResolution` override every material.
// With `group` (one of several processes), each frame's tiles are shared
// among them and only process 0's frames are whole. `prefillPerFrame`:
// RayCacheSettings::prefillTexelsPerFrame. `resolutionFromView`, `fill`:
// RayCacheSettings::resolutionFromView, visibleFill. `improvements`:
// RayCacheSettings::cdctImprovements. `policy`, `policyCosts`: RayCacheSettings::policy, policyCosts.
PathRender renderPath(const std::string& sceneName, CacheTechnique technique, int frames, bool still, int size,
                      int threads = 2, int cacheResolution = 512, const ProcessGroup* group = nullptr,
                      TileBalance balance = TileBalance::Dynamic, int cubeLevels = 1,
                      std::int64_t prefillPerFrame = 0, bool resolutionFromView = false,
                      VisibleFill fill = VisibleFill::Off, const CdctImprovements& improvements = {},
                      CachePolicyMode policy = CachePolicyMode::Always, const CachePolicyCosts& policyCosts = {});
// The same for a scene of the caller's.
PathRender renderPath(const Scene& scene, CacheTechnique technique, int frames, bool still, int size,
                      int threads = 2, int cacheResolution = 512, const ProcessGroup* group = nullptr,
                      TileBalance balance = TileBalance::Dynamic, int cubeLevels = 1,
                      std::int64_t prefillPerFrame = 0, bool resolutionFromView = false,
                      VisibleFill fill = VisibleFill::Off, const CdctImprovements& improvements = {},
                      CachePolicyMode policy = CachePolicyMode::Always, const CachePolicyCosts& policyCosts = {});

}  // namespace raycache
