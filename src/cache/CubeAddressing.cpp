#include "cache/CubeAddressing.h"

#include <algorithm>

namespace raycache {

Vec3 cubeTexelCenterDirection(const CubeTexel& texel, int size) {
    const float n = static_cast<float>(size);
    const float sc = 2.0f * (static_cast<float>(texel.x) + 0.5f) / n - 1.0f;
    const float tc = 2.0f * (static_cast<float>(texel.y) + 0.5f) / n - 1.0f;
    // Inverse of the table in core/CubeMapping.h with |major| = 1.
    switch (texel.face) {
    case CubeFace::PosX: return {1.0f, -tc, -sc};
    case CubeFace::NegX: return {-1.0f, -tc, sc};
    case CubeFace::PosY: return {sc, 1.0f, tc};
    case CubeFace::NegY: return {sc, -1.0f, -tc};
    case CubeFace::PosZ: return {sc, -tc, 1.0f};
    case CubeFace::NegZ: return {-sc, -tc, -1.0f};
    }
    return {1.0f, 0.0f, 0.0f};
}

}  // namespace raycache
