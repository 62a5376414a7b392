#include "core/TextFormat.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace raycache {

namespace {

template <typename T>
std::string shortestText(T value) {
    if (value == std::floor(value) && std::fabs(value) < T(1e15)) return std::to_string(static_cast<long long>(value));
    std::array<char, 32> buffer{};
    const auto r = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), r.ptr);
}

}  // namespace

std::string formatFixed(double value, int decimals) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

std::string formatGeneral(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return buffer;
}

std::string formatShortest(double value) {
    return shortestText(value);
}

std::string formatShortestFloat(float value) {
    return shortestText(value);
}

}  // namespace raycache
