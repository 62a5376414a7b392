#include "cache/CubeCross.h"

namespace raycache {

CubeCrossCell cubeCrossCell(CubeFace face) {
    switch (face) {
    case CubeFace::PosY: return {1, 0};
    case CubeFace::NegX: return {0, 1};
    case CubeFace::PosZ: return {1, 1};
    case CubeFace::PosX: return {2, 1};
    case CubeFace::NegZ: return {3, 1};
    case CubeFace::NegY: return {1, 2};
    }
    return {0, 0};
}

Image unfoldCubeCross(const CachingCube& cube) {
    const int n = cube.size();
    Image image(4 * n, 3 * n);
    for (Rgb& pixel : image.pixels()) pixel = Rgb{kCubeCrossEmptyGrey};
    for (int f = 0; f < 6; ++f) {
        const CubeFace face = static_cast<CubeFace>(f);
        const CubeCrossCell cell = cubeCrossCell(face);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const auto color = cube.read(cubeTexelIndex({face, x, y}, n));
                image.at(cell.column * n + x, cell.row * n + y) = color.value_or(Rgb{0.0f});
            }
    }
    return image;
}

}  // namespace raycache
