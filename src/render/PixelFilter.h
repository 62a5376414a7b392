#pragma once
// The pixel filter of `--spp N` renders: Blackman-Harris over a pixel's
// neighbourhood, separable in x and y, as Cycles filters its samples with
// its default filter_width of 1.5 px. Cycles' filter table doubles that width
// for Blackman-Harris, so the window reaches 1.5 px either side of the pixel's
// centre (3 px across); this filter is that window, not an approximation.
#include <cmath>
#include <numbers>

namespace raycache {

struct PixelFilter {
    static constexpr float kRadius = 1.5f;  // pixels either side of the centre

    // The weight of a sample `d` pixels from the centre along one axis:
    // Blackman-Harris over [-kRadius, kRadius], 0 outside.
    static float weight1d(float d) {
        if (!(std::fabs(d) < kRadius)) return 0.0f;
        const double v = 2.0 * std::numbers::pi * (static_cast<double>(d) / (2.0 * kRadius) + 0.5);
        // cos 2v and cos 3v from cos v (Chebyshev's identities): one cosine, not three.
        const double c = std::cos(v);
        const double cos2 = 2.0 * c * c - 1.0, cos3 = c * (4.0 * c * c - 3.0);
        return static_cast<float>(0.35875 - 0.48829 * c + 0.14128 * cos2 - 0.01168 * cos3);
    }
    static float weight(float dx, float dy) { return weight1d(dx) * weight1d(dy); }
};

}  // namespace raycache
