#include "render/ImageWriter.h"

#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <string>
#include <system_error>
#include <vector>

#include "core/AtomicFile.h"
#include "core/ColorSpace.h"
#include "core/Errors.h"

namespace raycache {
namespace {

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

// Returns an error message, empty on success.
std::string savePng(const Image& image, const std::filesystem::path& file) {
    std::vector<unsigned char> bytes;
    bytes.reserve(image.pixels().size() * 3);
    for (const Rgb& px : image.pixels()) {
        bytes.push_back(linearToSrgb8(px.r));
        bytes.push_back(linearToSrgb8(px.g));
        bytes.push_back(linearToSrgb8(px.b));
    }
    if (!stbi_write_png(file.c_str(), image.width(), image.height(), 3, bytes.data(), image.width() * 3))
        return "cannot write PNG data";
    return {};
}

// Returns an error message, empty on success. Uses the full tinyexr API rather
// than SaveEXR, which leaks on failure and skips compression for small images.
std::string saveExr(const Image& image, const std::filesystem::path& file) {
    const std::size_t count = image.pixels().size();
    // EXR stores channels separately, in alphabetical order: B, G, R.
    std::vector<float> planes[3];
    for (auto& plane : planes) plane.reserve(count);
    for (const Rgb& px : image.pixels()) {
        planes[0].push_back(px.b);
        planes[1].push_back(px.g);
        planes[2].push_back(px.r);
    }
    float* planePtrs[3] = {planes[0].data(), planes[1].data(), planes[2].data()};

    EXRImage exrImage;
    InitEXRImage(&exrImage);
    exrImage.num_channels = 3;
    exrImage.images = reinterpret_cast<unsigned char**>(planePtrs);
    exrImage.width = image.width();
    exrImage.height = image.height();

    EXRChannelInfo channels[3]{};
    int pixelTypes[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
    const char* names[3] = {"B", "G", "R"};
    for (int c = 0; c < 3; ++c) std::strcpy(channels[c].name, names[c]);

    EXRHeader header;
    InitEXRHeader(&header);
    header.num_channels = 3;
    header.channels = channels;
    header.pixel_types = pixelTypes;
    header.requested_pixel_types = pixelTypes;  // float in, float out: bit-exact
    header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;

    const char* err = nullptr;
    const int code = SaveEXRImageToFile(&exrImage, &header, file.c_str(), &err);
    if (code == TINYEXR_SUCCESS) return {};
    std::string message = err ? err : "tinyexr error code " + std::to_string(code);
    if (err) FreeEXRErrorMessage(err);
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
    return message;
}

}  // namespace

bool isSupportedImageExtension(const std::filesystem::path& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".png" || ext == ".exr";
}

void checkWritableImagePath(const std::filesystem::path& path) {
    const InputLocation where{.file = path.string()};
    if (!isSupportedImageExtension(path))
        throw InputError(where, "unsupported output image format '" + path.extension().string() +
                                    "' (expected .png or .exr)");
    // An empty parent means the current directory, which exists.
    const std::filesystem::path parent = path.parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
        throw InputError(where, "output directory '" + parent.string() + "' does not exist");
}

void writeImage(const Image& image, const std::filesystem::path& path) {
    checkWritableImagePath(path);
    if (image.empty())
        throw RuntimeError("cannot write " + path.string() + ": the image is empty");

    const bool png = lowerExtension(path) == ".png";
    writeFileAtomically(path, [&](const std::filesystem::path& temp) {
        const std::string error = png ? savePng(image, temp) : saveExr(image, temp);
        if (!error.empty()) throw RuntimeError(error);
    });
}

}  // namespace raycache
