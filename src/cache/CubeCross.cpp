#include "cache/CubeCross.h"

#include <algorithm>
#include <cmath>

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

namespace {

// The cross with texel (face, x, y) drawn as pixelOf(texel index).
template <typename PixelOf>
Image unfold(int n, const PixelOf& pixelOf) {
    Image image(4 * n, 3 * n);
    for (Rgb& pixel : image.pixels()) pixel = Rgb{kCubeCrossEmptyGrey};
    for (int f = 0; f < 6; ++f) {
        const CubeFace face = static_cast<CubeFace>(f);
        const CubeCrossCell cell = cubeCrossCell(face);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                image.at(cell.column * n + x, cell.row * n + y) = pixelOf(cubeTexelIndex({face, x, y}, n));
    }
    return image;
}

}  // namespace

Image unfoldCubeCross(const CachingCube& cube) {
    return unfold(cube.size(), [&](int texel) { return cube.read(texel).value_or(Rgb{0.0f}); });
}

Image unfoldCubeDepthCross(const CachingCube& cube, float maxDepth) {
    float nearest = maxDepth, farthest = 0.0f;
    for (std::size_t i = 0; i < cube.texelCount(); ++i) {
        const float d = cube.depth(static_cast<int>(i));
        if (!cube.isValid(static_cast<int>(i)) || d >= maxDepth) continue;
        nearest = std::min(nearest, d);
        farthest = std::max(farthest, d);
    }
    const float span = std::log(std::max(farthest, nearest * 1.0001f) / nearest);
    return unfold(cube.size(), [&](int texel) {
        if (!cube.isValid(texel)) return Rgb{1.0f, 0.0f, 0.0f};
        const float d = cube.depth(texel);
        if (d >= maxDepth) return Rgb{0.05f, 0.1f, 0.4f};
        const float grey = 1.0f - std::clamp(std::log(d / nearest) / span, 0.0f, 1.0f);
        return Rgb{grey * grey};  // roughly perceptual steps once written as sRGB
    });
}

}  // namespace raycache
