#pragma once
// Reads an OpenEXR file into linear float RGB through OpenEXR itself.
#include <filesystem>

#include "core/Image.h"

namespace raycache {

// Reads the first part of `path`: scanline or tiled (level 0 of a mip- or
// ripmap), any compression OpenEXR offers, half or float channels. The image
// is the part's data window, its top-left pixel at (0, 0) wherever the window
// lies. Colour comes from the channels R, G and B; without them from Y, or
// from the only channel, as grey; alpha and any other channel are ignored.
// Throws InputError naming the file, in one line, for anything else: a file
// that is not OpenEXR or is corrupt or truncated, a deep part, colour stored
// as 32-bit integers or subsampled, no colour channels, a side larger than
// maxImageSide (scene/ImageLoader.h), a block larger than the reader buffers
// (maxExrBlockBytes), or a value that is not finite.
Image readExrImage(const std::filesystem::path& path);

// Most bytes the reader lets OpenEXR buffer at once: one block of the file
// unpacked (a tile or a group of scanlines, every channel) and, for tiled
// files, one row of tiles of the colour channels. A larger claim is refused
// from the header, before OpenEXR allocates for it: a legitimate block is far
// smaller (a 16384-pixel-wide DWAB block, 256 rows of four float channels, is
// 64 MiB).
inline constexpr unsigned long long maxExrBlockBytes = 256ull << 20;

}  // namespace raycache
