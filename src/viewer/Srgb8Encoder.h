#pragma once
// Fast linear -> 8-bit sRGB for displaying a film every frame. Gives exactly
// linearToSrgb8 (core/ColorSpace.h), the encoding PNG files get, without a
// pow() per channel: a table of the 255 thresholds between codes, entered
// through a table indexed by the float's top bits.
#include <array>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "core/DisplayTransform.h"
#include "core/Image.h"

namespace raycache {

class Srgb8Encoder {
public:
    Srgb8Encoder();

    // Equals linearToSrgb8(linear) for every float, NaN and infinities included.
    unsigned char encode(float linear) const {
        if (!(linear > 0.0f)) return 0;
        if (linear >= thresholds_[255]) return 255;
        int code = bucketStart_[std::bit_cast<std::uint32_t>(linear) >> kBucketShift];
        while (linear >= thresholds_[static_cast<std::size_t>(code) + 1]) ++code;
        return static_cast<unsigned char>(code);
    }

    // Writes rows [y0, y1) of `image` as RGBA (alpha 255) into `rgba`, which
    // holds the whole image (4 bytes per pixel, row 0 first). With `display`
    // (not the identity), each pixel goes through it first.
    void encodeRows(const Image& image, int y0, int y1, std::span<std::uint8_t> rgba,
                    const DisplayTransform* display = nullptr) const;

    // The smallest positive float that encodes to `code` or more (code 1..255).
    float threshold(int code) const { return thresholds_[static_cast<std::size_t>(code)]; }

private:
    static constexpr int kBucketShift = 15;
    std::array<float, 257> thresholds_{};  // [0] = 0, [256] = +inf
    std::vector<std::uint8_t> bucketStart_;
};

}  // namespace raycache
