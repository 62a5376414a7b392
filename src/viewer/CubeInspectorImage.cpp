#include "viewer/CubeInspectorImage.h"

#include <algorithm>

#include "cache/CubeCross.h"

namespace raycache {

Image cubeInspectorImage(const CachingCube& cube, int maxFaceSize, std::span<const std::uint64_t> dropped) {
    const int n = cube.size();
    const int s = std::clamp(maxFaceSize, 1, n);
    Image image(4 * s, 3 * s);
    for (Rgb& pixel : image.pixels()) pixel = Rgb{kCubeCrossEmptyGrey};
    for (int f = 0; f < 6; ++f) {
        const auto face = static_cast<CubeFace>(f);
        const CubeCrossCell cell = cubeCrossCell(face);
        for (int y = 0; y < s; ++y) {
            const int ty = static_cast<int>(static_cast<long>(y) * n / s);
            for (int x = 0; x < s; ++x) {
                const int tx = static_cast<int>(static_cast<long>(x) * n / s);
                const int index = cubeTexelIndex({face, tx, ty}, n);
                const auto color = cube.read(index);
                Rgb shown = color.value_or(Rgb{0.0f});
                const auto i = static_cast<std::size_t>(index);
                if (!dropped.empty() && ((dropped[i >> 6] >> (i & 63)) & 1u))
                    shown = color ? (shown + kDroppedMagenta) * 0.5f : kDroppedMagenta;
                image.at(cell.column * s + x, cell.row * s + y) = shown;
            }
        }
    }
    return image;
}

}  // namespace raycache
