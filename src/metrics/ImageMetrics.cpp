#include "metrics/ImageMetrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/ColorSpace.h"
#include "core/Errors.h"

namespace raycache {

namespace {

template <typename Accumulate>
void forEachChannelPair(const Image& a, const Image& b, Accumulate&& accumulate) {
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError("images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) +
                         " vs " + std::to_string(b.width()) + "x" + std::to_string(b.height()));
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        const Rgb& p = a.pixels()[i];
        const Rgb& q = b.pixels()[i];
        accumulate(displayedValue(p.r) - displayedValue(q.r));
        accumulate(displayedValue(p.g) - displayedValue(q.g));
        accumulate(displayedValue(p.b) - displayedValue(q.b));
    }
}

}  // namespace

double meanAbsoluteError(const Image& a, const Image& b) {
    double sum = 0.0;
    forEachChannelPair(a, b, [&](float d) { sum += std::fabs(d); });
    return a.pixels().empty() ? 0.0 : sum / (3.0 * static_cast<double>(a.pixels().size()));
}

double psnr(const Image& a, const Image& b) {
    double sum = 0.0;
    forEachChannelPair(a, b, [&](float d) { sum += static_cast<double>(d) * d; });
    const double mse = a.pixels().empty() ? 0.0 : sum / (3.0 * static_cast<double>(a.pixels().size()));
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(1.0 / mse);
}

double maskedPsnr(const Image& a, const Image& b, std::span<const unsigned char> mask) {
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError("images differ in size: " + std::to_string(a.width()) + "x" + std::to_string(a.height()) +
                         " vs " + std::to_string(b.width()) + "x" + std::to_string(b.height()));
    if (mask.size() != a.pixels().size())
        throw InputError("mask has " + std::to_string(mask.size()) + " entries for " +
                         std::to_string(a.pixels().size()) + " pixels");
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        const Rgb& p = a.pixels()[i];
        const Rgb& q = b.pixels()[i];
        for (const double d :
             {static_cast<double>(displayedValue(p.r) - displayedValue(q.r)), static_cast<double>(displayedValue(p.g) - displayedValue(q.g)),
              static_cast<double>(displayedValue(p.b) - displayedValue(q.b))})
            sum += d * d;
        ++count;
    }
    if (count == 0) return std::numeric_limits<double>::quiet_NaN();
    const double mse = sum / (3.0 * static_cast<double>(count));
    if (mse == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(1.0 / mse);
}

long countNonFinitePixels(const Image& image) {
    return std::count_if(image.pixels().begin(), image.pixels().end(), [](const Rgb& p) { return !p.isFinite(); });
}

}  // namespace raycache
