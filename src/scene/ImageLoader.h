#pragma once
// Reads textures and environment maps from disk into linear float RGB.
#include <filesystem>

#include "core/Image.h"

namespace raycache {

// PNG, JPEG, BMP and TGA are taken as 8-bit sRGB and converted to linear;
// Radiance .hdr and OpenEXR .exr are already linear (which EXR files are read,
// and how: scene/ExrImageReader.h). Alpha is dropped. The format is chosen by
// the (case-insensitive) extension. Throws InputError
// naming the file if it is missing, unreadable, corrupt, of an unsupported
// format, empty, larger than maxImageSide per side, or holds non-finite values.
Image loadImageFile(const std::filesystem::path& path);

// Largest accepted width or height; anything bigger is almost surely a corrupt
// header, and would cost gigabytes.
inline constexpr int maxImageSide = 16384;

}  // namespace raycache
