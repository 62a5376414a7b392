// Texture::sample of an image against the rule it implements, written here
// plainly (std::floor and a modulo wrap): repeat, texel centres at
// half-integers, bilinear, v = 0 the image's bottom row. Bit for bit, at
// coordinates of every kind: inside, negative, whole numbers, a hair below
// them (where u - floor(u) rounds to 1), beyond 2^23 (where floats are whole)
// and not finite.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "scene/Texture.h"

namespace raycache {
namespace {

int wrapped(int i, int n) {
    const int m = i % n;
    return m < 0 ? m + n : m;
}

Rgb bilinearRepeat(const Image& img, float u, float v) {
    const float x = (u - std::floor(u)) * static_cast<float>(img.width()) - 0.5f;
    const float y = (1.0f - (v - std::floor(v))) * static_cast<float>(img.height()) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float ax = x - fx, ay = y - fy;
    const int x0 = wrapped(static_cast<int>(fx), img.width()), x1 = wrapped(x0 + 1, img.width());
    const int y0 = wrapped(static_cast<int>(fy), img.height()), y1 = wrapped(y0 + 1, img.height());
    const Rgb top = img.at(x0, y0) * (1.0f - ax) + img.at(x1, y0) * ax;
    const Rgb bottom = img.at(x0, y1) * (1.0f - ax) + img.at(x1, y1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

bool sameBits(const Rgb& a, const Rgb& b) {
    return std::bit_cast<std::uint32_t>(a.r) == std::bit_cast<std::uint32_t>(b.r) &&
           std::bit_cast<std::uint32_t>(a.g) == std::bit_cast<std::uint32_t>(b.g) &&
           std::bit_cast<std::uint32_t>(a.b) == std::bit_cast<std::uint32_t>(b.b);
}

TEST(TextureSample, ImagesFilterAsTheBilinearRepeatRule) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (const auto& [width, height] : std::vector<std::pair<int, int>>{{1, 1}, {2, 3}, {7, 5}, {64, 16}}) {
        auto image = std::make_shared<Image>(width, height);
        for (Rgb& p : image->pixels()) p = Rgb{value(rng), value(rng), value(rng)};
        const Texture texture = Texture::image(image);
        std::vector<float> coordinates = {0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 3.0f, -1e-9f, 1e-9f, 1.0f - 1e-8f,
                                          -2.0f - 1e-7f, 8388607.5f, 8388608.0f, -8388609.0f, 1e12f, -3e20f};
        std::uniform_real_distribution<float> near(-3.0f, 3.0f), far(-1e6f, 1e6f);
        for (int i = 0; i < 2000; ++i) coordinates.push_back(i % 2 ? near(rng) : far(rng));
        for (std::size_t i = 0; i < coordinates.size(); ++i) {
            const float u = coordinates[i], v = coordinates[(i * 7 + 3) % coordinates.size()];
            ASSERT_TRUE(sameBits(texture.sample(u, v), bilinearRepeat(*image, u, v)))
                << width << "x" << height << " at (" << u << ", " << v << ")";
        }
        // Not finite: a NaN colour, and no read outside the image (ASan).
        for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
            EXPECT_TRUE(std::isnan(texture.sample(bad, 0.25f).r));
            EXPECT_TRUE(std::isnan(texture.sample(0.25f, -bad).g));
        }
    }
}

}  // namespace
}  // namespace raycache
