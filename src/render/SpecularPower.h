#pragma once
// x^shininess for the Blinn-Phong highlight, the same bits on every target
// and in every code path (scalar, lanes): by repeated squaring for whole
// exponents up to 65535, each multiplication one IEEE product; std::pow
// (glibc, the same on every target) for any other exponent.
#include <cmath>

namespace raycache {

inline float specularPower(float x, float shininess) {
    const bool whole = shininess >= 0.0f && shininess <= 65535.0f &&
                       static_cast<float>(static_cast<int>(shininess)) == shininess;
    if (!whole) return std::pow(x, shininess);
    auto exponent = static_cast<unsigned>(shininess);
    float result = 1.0f, base = x;
    while (exponent != 0) {
        if (exponent & 1u) result *= base;
        exponent >>= 1;
        if (exponent != 0) base *= base;
    }
    return result;
}

}  // namespace raycache
