#pragma once
// RGB9E5: three 9-bit mantissas sharing one 5-bit exponent in 32 bits (the
// EXT_texture_shared_exponent format). A caching cube stores one per texel:
// 4 bytes instead of 12 for float RGB, ~0.2 % relative precision.
//
// The all-ones word is reserved as "no color" (an invalid texel): encode()
// clamps below the largest representable value, so it never produces it.
#include <cstdint>

#include "core/Rgb.h"

namespace raycache {

class SharedExponentColor {
public:
    static constexpr std::uint32_t kInvalid = 0xFFFFFFFFu;
    // Largest channel value encode() keeps; brighter values are clamped.
    static constexpr float kMaxValue = 65000.0f;

    // Negative and NaN channels become 0; channels above kMaxValue are clamped.
    static std::uint32_t encode(const Rgb& color);
    static Rgb decode(std::uint32_t packed);
};

}  // namespace raycache
