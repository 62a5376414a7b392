#include "viewer/Srgb8Encoder.h"

#include <limits>

#include "core/ColorSpace.h"

namespace raycache {

Srgb8Encoder::Srgb8Encoder() {
    // linearToSrgb8 is monotonic in its argument, and positive floats are
    // ordered like their bit patterns: bisect the bits for each threshold.
    const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);  // encodes to 255
    for (int code = 1; code <= 255; ++code) {
        std::uint32_t lo = 0, hi = one;  // linearToSrgb8(lo) < code <= linearToSrgb8(hi)
        while (hi - lo > 1) {
            const std::uint32_t mid = lo + (hi - lo) / 2;
            if (linearToSrgb8(std::bit_cast<float>(mid)) >= code) hi = mid;
            else lo = mid;
        }
        thresholds_[static_cast<std::size_t>(code)] = std::bit_cast<float>(hi);
    }
    thresholds_[256] = std::numeric_limits<float>::infinity();
    const std::uint32_t buckets = (std::bit_cast<std::uint32_t>(thresholds_[255]) >> kBucketShift) + 1;
    bucketStart_.resize(buckets);
    for (std::uint32_t b = 0; b < buckets; ++b)
        bucketStart_[b] = linearToSrgb8(std::bit_cast<float>(b << kBucketShift));
}

void Srgb8Encoder::encodeRows(const Image& image, int y0, int y1, std::span<std::uint8_t> rgba,
                              const DisplayTransform* display) const {
    if (display && display->identity()) display = nullptr;
    const auto width = static_cast<std::size_t>(image.width());
    for (int y = y0; y < y1; ++y) {
        std::uint8_t* out = rgba.data() + static_cast<std::size_t>(y) * width * 4;
        for (int x = 0; x < image.width(); ++x) {
            const Rgb p = display ? (*display)(image.at(x, y)) : image.at(x, y);
            *out++ = encode(p.r);
            *out++ = encode(p.g);
            *out++ = encode(p.b);
            *out++ = 255;
        }
    }
}

}  // namespace raycache
