#pragma once
// Direction -> cube face and face coordinates, following the OpenGL cubemap
// convention (OpenGL 4.6 core, table 8.19). Used by cube-face environments and
// caching cubes. Faces are numbered as GL's targets: +x, -x, +y, -y, +z, -z.
//
// The table fixes the mapping but not the float arithmetic, the tie-breaking
// or signed zeros; here they are exactly Mesa's llvmpipe (gallivm,
// lp_build_cube_lookup), so that a texel addressed here is the texel GL reads
// (tests/cache/CubeAddressingGlTest.cpp holds this against real OpenGL).
#include <cfloat>
#include <cmath>

#include "core/Vec3.h"

namespace raycache {

enum class CubeFace : int { PosX = 0, NegX = 1, PosY = 2, NegY = 3, PosZ = 4, NegZ = 5 };

struct CubeCoord {
    CubeFace face;
    float s;  // [0,1], increasing to the right of the face image
    float t;  // [0,1], increasing downward in the face image (GL's t with images stored top row first)
};

// llvmpipe runs shaders with denormals-are-zero and flush-to-zero set, so a
// subnormal input behaves as a zero of the same sign, and a subnormal result
// becomes +0. Doing it by hand keeps the answers independent of this thread's
// MXCSR.
inline float flushSubnormal(float v) {
    return std::fabs(v) < FLT_MIN ? std::copysign(0.0f, v) : v;
}

// a * b rounded to float on its own. llvmpipe emits a separate multiply and
// add; GCC would fuse `a * b + c` into one FMA (one rounding) wherever FMA is
// enabled (-march=native), even across statements, and change the answer.
// An empty asm that takes and gives back the product in a register forbids
// that on GCC and clang alike (the compiler cannot see through it), without
// the memory round trip a volatile variable costs every cache lookup.
inline float roundedProduct(float a, float b) {
#if defined(__x86_64__)
    float product = a * b;
    asm("" : "+x"(product));
#else
    volatile float product = a * b;
#endif
    return product;
}

// GL table 8.19 with llvmpipe's decisions:
//  - major axis: z if |z| >= max(|x|, |y|), else x if |x| > |y|, else y
//    (ties prefer z over y over x);
//  - positive or negative face from the sign bit of the major component, so
//    -0 counts as negative (only matters when all components are zero);
//  - s = sc * (0.5 / |ma|) + 0.5, each operation rounded to float (an IEEE
//    division, not a reciprocal estimate), and likewise t; 0.5 / |ma| is 0
//    when |ma| is 0 (or flushes to 0 when |ma| > 2^125).
// Components below FLT_MIN count as zero (see flushSubnormal). Not for
// infinite or NaN components.
inline CubeCoord cubeCoordFromDirection(const Vec3& direction) {
    const Vec3 d{flushSubnormal(direction.x), flushSubnormal(direction.y), flushSubnormal(direction.z)};
    const float ax = std::fabs(d.x);
    const float ay = std::fabs(d.y);
    const float az = std::fabs(d.z);
    CubeFace face;
    float sc, tc, ma;
    // max(|x|, |y|) of non-NaN magnitudes: std::fmax's answer, without its
    // call into libm (GCC keeps fmaxf a call for the sake of NaNs).
    if (az >= (ax < ay ? ay : ax)) {
        ma = d.z;
        face = std::signbit(ma) ? CubeFace::NegZ : CubeFace::PosZ;
        sc = std::signbit(ma) ? -d.x : d.x;
        tc = -d.y;
    } else if (ax > ay) {
        ma = d.x;
        face = std::signbit(ma) ? CubeFace::NegX : CubeFace::PosX;
        sc = std::signbit(ma) ? d.z : -d.z;
        tc = -d.y;
    } else {
        ma = d.y;
        face = std::signbit(ma) ? CubeFace::NegY : CubeFace::PosY;
        sc = d.x;
        tc = std::signbit(ma) ? -d.z : d.z;
    }
    const float absMa = std::fabs(ma);
    const float halfInverseMa = absMa > 0.0f ? flushSubnormal(0.5f / absMa) : 0.0f;
    return {face, roundedProduct(sc, halfInverseMa) + 0.5f, roundedProduct(tc, halfInverseMa) + 0.5f};
}

}  // namespace raycache
