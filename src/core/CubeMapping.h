#pragma once
// Direction -> cube face and face coordinates, following the OpenGL cubemap
// convention (OpenGL 4.6 core, table 8.19). Used by cube-face environments and,
// later, caching cubes. Faces are numbered as GL's targets: +x, -x, +y, -y, +z, -z.
#include "core/Vec3.h"

namespace raycache {

enum class CubeFace : int { PosX = 0, NegX = 1, PosY = 2, NegY = 3, PosZ = 4, NegZ = 5 };

struct CubeCoord {
    CubeFace face;
    float s;  // [0,1], increasing to the right of the face image
    float t;  // [0,1], increasing downward in the face image (GL's t with images stored top row first)
};

// Major axis = largest |component|; ties go to x over y over z, as Mesa does.
// A zero major component gives the positive face (-0 >= 0).
inline CubeCoord cubeCoordFromDirection(const Vec3& d) {
    const float ax = d.x < 0 ? -d.x : d.x;
    const float ay = d.y < 0 ? -d.y : d.y;
    const float az = d.z < 0 ? -d.z : d.z;
    CubeFace face;
    float sc, tc, ma;
    if (ax >= ay && ax >= az) {
        ma = ax;
        face = d.x >= 0.0f ? CubeFace::PosX : CubeFace::NegX;
        sc = d.x >= 0.0f ? -d.z : d.z;
        tc = -d.y;
    } else if (ay >= az) {
        ma = ay;
        face = d.y >= 0.0f ? CubeFace::PosY : CubeFace::NegY;
        sc = d.x;
        tc = d.y >= 0.0f ? d.z : -d.z;
    } else {
        ma = az;
        face = d.z >= 0.0f ? CubeFace::PosZ : CubeFace::NegZ;
        sc = d.z >= 0.0f ? d.x : -d.x;
        tc = -d.y;
    }
    return {face, 0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)};
}

}  // namespace raycache
