#pragma once
// cubeTexelIndex(cubeTexelFromDirection(d, size), size) for sixteen
// directions at once: the tile kernel addresses the texels of the rays that
// leave a CCT object while it spawns them in lanes (render/TileKernelWaves.cpp),
// so the cache's lookup batch need not address them one at a time. The same
// IEEE operations as the scalar form, lane by lane, so the same texels on
// every x86-64 level (tests/cache/CubeAddressingLanesTest.cpp).

namespace raycache {

// For each lane k with lanes[k] != 0: texels[k] = the face-major index of
// the texel direction (x[k], y[k], z[k]) addresses on a cube of `size`
// texels per face side. Other lanes of `texels` are left as they are.
// Directions as cubeTexelFromDirection takes them: finite, any length.
void cubeTexelIndices16(const float* x, const float* y, const float* z, int size, const int* lanes, int* texels);

}  // namespace raycache
