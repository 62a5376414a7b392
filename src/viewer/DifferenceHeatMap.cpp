#include "viewer/DifferenceHeatMap.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace raycache {

void heatMapColor(float d, std::uint8_t rgb[3]) {
    // Five stops: blue, cyan, green, yellow, red.
    static constexpr float kStops[5][3] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
    const float t = std::clamp(std::isnan(d) ? 1.0f : d, 0.0f, 1.0f) * 4.0f;
    const int i = std::min(static_cast<int>(t), 3);
    const float f = t - static_cast<float>(i);
    for (int c = 0; c < 3; ++c) {
        const float v = kStops[i][c] + (kStops[i + 1][c] - kStops[i][c]) * f;
        rgb[c] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
}

double differenceHeatMap(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b, float gain,
                         std::span<std::uint8_t> out) {
    const std::size_t pixels = std::min({a.size(), b.size(), out.size()}) / 4;
    double sum = 0.0;
    for (std::size_t i = 0; i < pixels; ++i) {
        const std::uint8_t* p = &a[4 * i];
        const std::uint8_t* q = &b[4 * i];
        const int total = std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]);
        const float d = static_cast<float>(total) / (3.0f * 255.0f);
        sum += d;
        heatMapColor(d * gain, &out[4 * i]);
        out[4 * i + 3] = 255;
    }
    return sum;
}

}  // namespace raycache
