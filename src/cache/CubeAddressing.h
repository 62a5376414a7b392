#pragma once
// Which texel of a caching cube a direction addresses: OpenGL's cubemap
// face selection (GL 4.6 table 8.19) and nearest-texel rule for a size x size
// face, computed in float exactly as Mesa's llvmpipe samples a cubemap, so a
// rasterizer sampling the cube with GL_NEAREST reads the same texel.
// tests/cache/CubeAddressingGlTest.cpp checks this against real OpenGL.
#include <algorithm>

#include "core/CubeMapping.h"
#include "core/Vec3.h"

namespace raycache {

struct CubeTexel {
    CubeFace face = CubeFace::PosX;
    int x = 0;  // column, 0 = left of the face image
    int y = 0;  // row, 0 = top of the face image (GL's t = 0)

    bool operator==(const CubeTexel&) const = default;
};

// The texel GL_NEAREST / GL_CLAMP_TO_EDGE sampling reads for `direction`
// (finite, any length) on a cube with `size` texels per face side. Ties
// between |components| and signed zeros are decided as llvmpipe does (see
// cubeCoordFromDirection); an all-zero direction gives the centre of +z or -z.
// Inline: every cache lookup and store addresses a texel.
inline CubeTexel cubeTexelFromDirection(const Vec3& direction, int size) {
    const CubeCoord c = cubeCoordFromDirection(direction);
    const float n = static_cast<float>(size);
    // GL nearest filtering with clamp-to-edge, i = clamp(floor(s * size), 0, size - 1),
    // as llvmpipe computes it (lp_build_sample_wrap_nearest): the product rounded
    // to float, truncated toward zero (same as floor once clamped at 0; s can
    // round to a hair below 0 or reach 1 on a face edge).
    const int x = std::clamp(static_cast<int>(c.s * n), 0, size - 1);
    const int y = std::clamp(static_cast<int>(c.t * n), 0, size - 1);
    return {c.face, x, y};
}

// Index of a texel in a face-major array: ((face * size) + y) * size + x.
inline int cubeTexelIndex(const CubeTexel& t, int size) {
    return (static_cast<int>(t.face) * size + t.y) * size + t.x;
}

// A direction that addresses texel (face, x, y): through the texel centre.
Vec3 cubeTexelCenterDirection(const CubeTexel& texel, int size);

}  // namespace raycache
