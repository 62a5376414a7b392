#pragma once
// scene/Texture::sample's checkerboard at sixteen points of one triangle at
// once, lane by lane with the same IEEE operations (the same squares): the
// texture re-fetch of a row's textured samples meets mostly one triangle,
// and one texture call at a time, with the point's texture coordinates,
// cost ~80 instructions a sample.
#include <array>

#include "core/FloatLanes.h"
#include "scene/Texture.h"

namespace raycache {

// The texture coordinates of a triangle's three corners (render/SurfacePoint's albedoAtHit).
using CornerTextureCoordinates = std::array<std::array<float, 2>, 3>;

// For lanes k < 16 at barycentrics (u[k], v[k]) on a triangle whose corners
// have texture coordinates `uv`: odd[k] is 1 where pattern's
// Texture::sample at the point's texture coordinates (albedoAtHit's sums)
// gives `pattern.odd`, 0 where it gives `pattern.even`.
void checkerSquares16(const Checkerboard& pattern, const CornerTextureCoordinates& uv, const float* u, const float* v,
                      int* odd);

}  // namespace raycache
