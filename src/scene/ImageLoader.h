#pragma once
// Reads textures and environment maps from disk into linear float RGB.
#include <filesystem>
#include <span>
#include <string>

#include "core/Image.h"

namespace raycache {

// PNG, JPEG, BMP and TGA are taken as 8-bit sRGB and converted to linear;
// Radiance .hdr and OpenEXR .exr are already linear (which EXR files are read,
// and how: scene/ExrImageReader.h). Alpha is dropped. The format is chosen by
// the (case-insensitive) extension. Throws InputError
// naming the file if it is missing, unreadable, corrupt, of an unsupported
// format, empty, larger than maxImageSide per side, or holds non-finite values.
Image loadImageFile(const std::filesystem::path& path);

// What an 8-bit image's values mean: colours, sRGB-encoded (glTF's base
// colour and emissive textures), or data stored as value / 255 (glTF's
// metallic-roughness and normal textures, which must not be decoded).
enum class ImageEncoding { Srgb, Linear };

// An 8-bit image held in memory (a glTF file's embedded PNG or JPEG; BMP
// and TGA too), told apart by its content, taken as sRGB and converted to
// linear like loadImageFile's, or read as data (`encoding`). `label` names
// the image in errors as a file would be named ("scene.glb: image 0").
// Throws InputError as loadImageFile does; Radiance HDR data is refused (it
// would be tone-mapped silently).
Image decodeImageBytes(std::span<const unsigned char> bytes, const std::string& label,
                       ImageEncoding encoding = ImageEncoding::Srgb);

// Largest accepted width or height; anything bigger is almost surely a corrupt
// header, and would cost gigabytes.
inline constexpr int maxImageSide = 16384;

}  // namespace raycache
