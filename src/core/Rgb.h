#pragma once
// Linear RGB radiance/reflectance triple.
#include <algorithm>
#include <cmath>

namespace raycache {

struct Rgb {
    float r = 0.0f, g = 0.0f, b = 0.0f;

    constexpr Rgb() = default;
    constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Rgb(float v) : r(v), g(v), b(v) {}

    constexpr Rgb& operator+=(const Rgb& o) { r += o.r; g += o.g; b += o.b; return *this; }
    constexpr Rgb& operator*=(const Rgb& o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
    constexpr Rgb& operator*=(float s) { r *= s; g *= s; b *= s; return *this; }
    constexpr bool operator==(const Rgb&) const = default;

    constexpr bool isBlack() const { return r == 0.0f && g == 0.0f && b == 0.0f; }
    constexpr float maxComponent() const { return std::max(r, std::max(g, b)); }
    bool isFinite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr Rgb operator+(Rgb a, const Rgb& b) { return a += b; }
constexpr Rgb operator*(Rgb a, const Rgb& b) { return a *= b; }
constexpr Rgb operator*(Rgb a, float s) { return a *= s; }
constexpr Rgb operator*(float s, Rgb a) { return a *= s; }

}  // namespace raycache
