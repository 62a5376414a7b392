#pragma once
// Writes rendered images to disk, atomically: a reader never sees a partial file.
#include <filesystem>

#include "core/DisplayTransform.h"
#include "core/Image.h"

namespace raycache {

// True for the formats writeImage can produce: .png (8-bit sRGB) and .exr
// (32-bit float linear), case-insensitive.
bool isSupportedImageExtension(const std::filesystem::path& path);

// Throws InputError naming `path` if its extension is unsupported or its parent
// directory does not exist, so a bad output path is caught before rendering.
void checkWritableImagePath(const std::filesystem::path& path);

// Writes `image` (linear RGB) in the format chosen by the extension: a PNG
// shows it through `display` (exposure, view transform; the defaults give the
// values as they are), an EXR holds the linear values themselves. The data
// goes to a temporary file in the same directory which is then renamed onto
// `path`. Throws InputError for what checkWritableImagePath rejects, and
// RuntimeError naming `path` if writing fails (the temporary file is removed).
void writeImage(const Image& image, const std::filesystem::path& path, const DisplaySettings& display = {});

}  // namespace raycache
