#pragma once
// The checks every image decoder applies, each failure one InputError naming
// the file: a size within limits before pixels are decoded, and finite
// values after.
#include <filesystem>

#include "core/Image.h"

namespace raycache {

// Throws unless 0 < width, height <= maxImageSide (scene/ImageLoader.h).
// Takes 64-bit sides so that a corrupt header's sizes are checked, not wrapped.
void checkImageSize(const std::filesystem::path& path, long long width, long long height);

// Throws naming the first pixel, in row order, that holds a NaN or an infinity.
void checkImageFinite(const std::filesystem::path& path, const Image& image);

}  // namespace raycache
