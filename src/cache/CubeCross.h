#pragma once
// A caching cube's six faces unfolded into one picture, the horizontal cross
// of the thesis' Figure 3.3, for looking at what a cube has cached:
//
//          +Y
//     -X   +Z   +X   -Z
//          -Y
//
// Neighbouring cells share their edges on the cube (with GL's face
// orientation, see core/CubeMapping.h), so the picture is continuous across
// the cross's inner seams.
#include "cache/CachingCube.h"
#include "core/Image.h"

namespace raycache {

// Dark grey of the cells the cross leaves empty, so they differ from invalid (black) texels.
inline constexpr float kCubeCrossEmptyGrey = 0.1f;

// An image 4 * size wide and 3 * size high (size = cube.size()). Texel (x, y)
// of a face, y = 0 being the face's top row (core/CubeMapping.h), lands at
// (x, y) inside that face's cell; cells are, by (column, row): +Y (1, 0);
// -X (0, 1), +Z (1, 1), +X (2, 1), -Z (3, 1); -Y (1, 2). Valid texels show
// their decoded color, invalid ones black, the six empty cells
// kCubeCrossEmptyGrey. Linear RGB, like a rendered film.
Image unfoldCubeCross(const CachingCube& cube);

// The same cross for a CDCT cube's depths (CDCT cubes only): distance from
// the centre as grey, white nearest to black at the farthest surface
// (logarithmically, so near and far structure both show), texels holding
// the environment (depth = maxDepth) blue, invalid texels red.
Image unfoldCubeDepthCross(const CachingCube& cube, float maxDepth);

// The cell (column, row) of `face` in the cross, in units of one face.
struct CubeCrossCell {
    int column;
    int row;
};
CubeCrossCell cubeCrossCell(CubeFace face);

}  // namespace raycache
