#pragma once
// The cache inspector's picture: a caching cube unfolded as a cross (the
// layout of cache/CubeCross.h), at most `maxFaceSize` pixels per face so it
// can be rebuilt every frame while the cube fills.
#include "cache/CachingCube.h"
#include "core/Image.h"

#include <cstdint>
#include <span>

namespace raycache {

// A 4s x 3s image, s = min(cube.size(), maxFaceSize) (maxFaceSize >= 1).
// Face pixel (x, y) shows texel (x * n / s, y * n / s), n = cube.size(), so
// for s = n it equals unfoldCubeCross(cube). Invalid texels are black, the
// cells outside the cross kCubeCrossEmptyGrey.
// `dropped` (RayCache::droppedByLastChange, may be empty): texels the last
// change of an animated scene dropped are kDroppedMagenta while still
// invalid, and half magenta once filled again.
Image cubeInspectorImage(const CachingCube& cube, int maxFaceSize, std::span<const std::uint64_t> dropped = {});
inline constexpr Rgb kDroppedMagenta{1.0f, 0.0f, 1.0f};

}  // namespace raycache
