#include "rendercache/PointImage.h"

#include <bit>

namespace raycache {

void PointImage::reset(int width, int height, int margin) {
    width_ = width;
    height_ = height;
    margin_ = margin;
    stride_ = width + 2 * margin;
    keys_.assign(static_cast<std::size_t>(stride_) * static_cast<std::size_t>(height + 2 * margin), kEmptyKey);
}

std::uint64_t PointImage::pack(float depth, std::uint32_t slot) {
    return std::uint64_t{std::bit_cast<std::uint32_t>(depth)} << 32 | slot;
}

float PointImage::depthAt(int x, int y) const {
    return std::bit_cast<float>(static_cast<std::uint32_t>(keys_[index(x, y)] >> 32));
}

}  // namespace raycache
