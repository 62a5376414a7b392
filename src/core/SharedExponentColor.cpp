#include "core/SharedExponentColor.h"

#include <algorithm>
#include <bit>
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

// 2^k as a float, for k in [-126, 127]: built from its bits, as ldexp(1, k)
// would give it, without the library call (encode runs once per cache store).
float powerOfTwo(int k) { return std::bit_cast<float>(static_cast<std::uint32_t>(k + 127) << 23); }
}  // namespace

std::uint32_t SharedExponentColor::encode(const Rgb& color) {
    const float r = clampChannel(color.r), g = clampChannel(color.g), b = clampChannel(color.b);
    const float maxChannel = std::max({r, g, b});
    if (maxChannel == 0.0f) return 0u;
    // Shared exponent so the largest channel's mantissa fits in 9 bits
    // (EXT_texture_shared_exponent, section 3.8.x). The exponent frexp would
    // give (maxChannel = m * 2^exponent, m in [0.5, 1)) is read off the float's
    // bits; subnormals are far below the smallest exponent kept, so any value
    // under the clamp does for them.
    const auto exponentBits = static_cast<int>((std::bit_cast<std::uint32_t>(maxChannel) >> 23) & 0xffu);
    const int exponent = exponentBits == 0 ? -kExponentBias - 100 : exponentBits - 126;
    int biased = std::max(-kExponentBias - 1, exponent - 1) + 1 + kExponentBias;
    // Dividing by a power of two and multiplying by its inverse are both exact.
    float inverseScale = powerOfTwo(kExponentBias + kMantissaBits - biased);
    // Truncation is floor for these non-negative values, without a libm call.
    if (static_cast<std::uint32_t>(maxChannel * inverseScale + 0.5f) >= (1u << kMantissaBits)) {
        ++biased;
        inverseScale *= 0.5f;
    }
    biased = std::min(biased, kMaxBiasedExponent);
    const auto mantissa = [&](float v) {
        return std::min(static_cast<std::uint32_t>(v * inverseScale + 0.5f), (1u << kMantissaBits) - 1u);
    };
    return mantissa(r) | (mantissa(g) << 9) | (mantissa(b) << 18) | (static_cast<std::uint32_t>(biased) << 27);
}

Rgb SharedExponentColor::decode(std::uint32_t packed) {
    const int biased = static_cast<int>(packed >> 27);
    const float scale = powerOfTwo(biased - kExponentBias - kMantissaBits);
    return {static_cast<float>(packed & 511u) * scale, static_cast<float>((packed >> 9) & 511u) * scale,
            static_cast<float>((packed >> 18) & 511u) * scale};
}

}  // namespace raycache
