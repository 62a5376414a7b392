#include "core/SharedExponentColor.h"

#include <algorithm>
#include <cmath>

namespace raycache {

namespace {
constexpr int kMantissaBits = 9;
constexpr int kExponentBias = 15;
constexpr int kMaxBiasedExponent = 31;

float clampChannel(float v) {
    // !(v > 0) also catches NaN.
    return !(v > 0.0f) ? 0.0f : std::min(v, SharedExponentColor::kMaxValue);
}
}  // namespace

std::uint32_t SharedExponentColor::encode(const Rgb& color) {
    const float r = clampChannel(color.r), g = clampChannel(color.g), b = clampChannel(color.b);
    const float maxChannel = std::max({r, g, b});
    if (maxChannel == 0.0f) return 0u;
    // Shared exponent so the largest channel's mantissa fits in 9 bits
    // (EXT_texture_shared_exponent, section 3.8.x), computed with frexp to be exact.
    int exponent;
    std::frexp(maxChannel, &exponent);  // maxChannel = m * 2^exponent, m in [0.5, 1)
    int biased = std::max(-kExponentBias - 1, exponent - 1) + 1 + kExponentBias;
    float scale = std::ldexp(1.0f, biased - kExponentBias - kMantissaBits);
    if (std::floor(maxChannel / scale + 0.5f) >= static_cast<float>(1 << kMantissaBits)) {
        ++biased;
        scale *= 2.0f;
    }
    biased = std::min(biased, kMaxBiasedExponent);
    const auto mantissa = [&](float v) {
        return std::min(static_cast<std::uint32_t>(std::floor(v / scale + 0.5f)), (1u << kMantissaBits) - 1u);
    };
    return mantissa(r) | (mantissa(g) << 9) | (mantissa(b) << 18) | (static_cast<std::uint32_t>(biased) << 27);
}

Rgb SharedExponentColor::decode(std::uint32_t packed) {
    const int biased = static_cast<int>(packed >> 27);
    const float scale = std::ldexp(1.0f, biased - kExponentBias - kMantissaBits);
    return {static_cast<float>(packed & 511u) * scale, static_cast<float>((packed >> 9) & 511u) * scale,
            static_cast<float>((packed >> 18) & 511u) * scale};
}

}  // namespace raycache
