#include "rendercache/PointImage.h"

namespace raycache {

void PointImage::reset(int width, int height, int margin) {
    width_ = width;
    height_ = height;
    margin_ = margin;
    stride_ = width + 2 * margin;
    keys_.assign(static_cast<std::size_t>(stride_) * static_cast<std::size_t>(height + 2 * margin), kEmptyKey);
}

}  // namespace raycache
