#include "scene/Texture.h"

#include <cmath>

namespace raycache {

Texture Texture::checkerboard(const Checkerboard& pattern) {
    Texture t;
    t.checker_ = pattern;
    return t;
}

Texture Texture::image(std::shared_ptr<const Image> pixels) {
    Texture t;
    t.image_ = std::move(pixels);
    return t;
}

namespace {
// floor() without a libm call: x86-64's baseline has no rounding instruction.
// Out-of-range and NaN inputs map to 0 instead of overflowing the cast.
long long floorToInt(float x) {
    if (!(std::fabs(x) < 1e15f)) return 0;
    const auto i = static_cast<long long>(x);
    return static_cast<float>(i) > x ? i - 1 : i;
}

// std::floor(x), inlined: below 2^23 in magnitude through an int, above it
// x itself (every such float is whole). NaN and infinities stay as they are.
float floorInline(float x) {
    if (!(std::fabs(x) < 8388608.0f)) return x;
    const auto truncated = static_cast<float>(static_cast<int>(x));
    return truncated > x ? truncated - 1.0f : truncated;
}
}  // namespace

Rgb Texture::sample(float u, float v) const {
    if (!image_) {
        const long long cu = floorToInt(u * checker_.squaresPerUnit);
        const long long cv = floorToInt(v * checker_.squaresPerUnit);
        return ((cu + cv) & 1) == 0 ? checker_.even : checker_.odd;
    }
    const Image& img = *image_;
    const int width = img.width(), height = img.height();
    // Bilinear filtering with texel centres at half-integers. The repeat
    // leaves x and y in [-0.5, size - 0.5], so the texel to the left of
    // (above) the point is -1 ... size - 1, and wraps without a division.
    // (Per hit, every fetch of every textured surface comes here.)
    const float x = (u - floorInline(u)) * static_cast<float>(width) - 0.5f;
    const float y = (1.0f - (v - floorInline(v))) * static_cast<float>(height) - 0.5f;
    const float fx = floorInline(x), fy = floorInline(y);
    const float ax = x - fx, ay = y - fy;
    // A NaN coordinate (NaN colour) still reads texels in the image.
    const int left = fx >= 0.0f ? static_cast<int>(fx) : -1, up = fy >= 0.0f ? static_cast<int>(fy) : -1;
    const int x0 = left < 0 ? left + width : left, x1 = x0 + 1 < width ? x0 + 1 : 0;
    const int y0 = up < 0 ? up + height : up, y1 = y0 + 1 < height ? y0 + 1 : 0;
    const Rgb top = img.at(x0, y0) * (1.0f - ax) + img.at(x1, y0) * ax;
    const Rgb bottom = img.at(x0, y1) * (1.0f - ax) + img.at(x1, y1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

}  // namespace raycache
