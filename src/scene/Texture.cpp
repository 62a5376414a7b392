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

int wrap(int i, int n) {
    const int m = i % n;
    return m < 0 ? m + n : m;
}
}  // namespace

Rgb Texture::sample(float u, float v) const {
    if (!image_) {
        const long long cu = floorToInt(u * checker_.squaresPerUnit);
        const long long cv = floorToInt(v * checker_.squaresPerUnit);
        return ((cu + cv) & 1) == 0 ? checker_.even : checker_.odd;
    }
    const Image& img = *image_;
    // Bilinear filtering with texel centres at half-integers.
    const float x = (u - std::floor(u)) * static_cast<float>(img.width()) - 0.5f;
    const float y = (1.0f - (v - std::floor(v))) * static_cast<float>(img.height()) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const int x0 = wrap(static_cast<int>(fx), img.width()), x1 = wrap(x0 + 1, img.width());
    const int y0 = wrap(static_cast<int>(fy), img.height()), y1 = wrap(y0 + 1, img.height());
    const Rgb top = img.at(x0, y0) * (1.0f - ax) + img.at(x1, y0) * ax;
    const Rgb bottom = img.at(x0, y1) * (1.0f - ax) + img.at(x1, y1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

}  // namespace raycache
