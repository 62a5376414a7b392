#include "scene/ImageLoader.h"

#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <system_error>

#include "core/ColorSpace.h"
#include "core/Errors.h"
#include "scene/ExrImageReader.h"
#include "scene/ImageFileChecks.h"

namespace raycache {
namespace {

// No format stb reads compresses pixels much better than deflate's ~1032:1,
// so a header claiming far more pixels than that for its bytes is corrupt.
constexpr std::uintmax_t kMaxPixelsPerByte = 1100;

enum class ImageFormat { Srgb8, RadianceHdr, OpenExr, Unsupported };

ImageFormat formatOf(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tga")
        return ImageFormat::Srgb8;
    if (ext == ".hdr") return ImageFormat::RadianceHdr;
    if (ext == ".exr") return ImageFormat::OpenExr;
    return ImageFormat::Unsupported;
}

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "unknown error";
}

// Reads the header first so that a corrupt or huge size is rejected before
// stb_image allocates for it.
void checkStbHeader(const std::filesystem::path& path) {
    int width = 0, height = 0, channels = 0;
    if (!stbi_info(path.c_str(), &width, &height, &channels))
        failFile(path.string(), "cannot read image: " + stbReason());
    checkImageSize(path, width, height);
    // Reject a corrupt header before stb allocates and clears it all (a
    // 33-byte TGA claiming 16384x10752 took 14 s under ASan).
    std::error_code error;
    const std::uintmax_t bytes = std::filesystem::file_size(path, error);
    const auto pixels = static_cast<std::uintmax_t>(width) * static_cast<std::uintmax_t>(height);
    if (!error && pixels > kMaxPixelsPerByte * bytes)
        failFile(path.string(), "header claims " + std::to_string(width) + "x" + std::to_string(height) + " pixels in a file of " +
                       std::to_string(bytes) + " bytes: corrupt");
}

// 8-bit sRGB, 3 channels as stb_image returns them, to linear; or, for
// data, each byte / 255.
Image linearFromSrgb8(const unsigned char* src, int width, int height, ImageEncoding encoding = ImageEncoding::Srgb) {
    std::array<float, 256> toLinear{};
    for (std::size_t i = 0; i < toLinear.size(); ++i) {
        const float value = static_cast<float>(i) / 255.0f;
        toLinear[i] = encoding == ImageEncoding::Srgb ? srgbToLinear(value) : value;
    }

    Image image(width, height);
    for (Rgb& px : image.pixels()) {
        px = Rgb(toLinear[src[0]], toLinear[src[1]], toLinear[src[2]]);
        src += 3;
    }
    return image;
}

Image loadSrgb8(const std::filesystem::path& path) {
    checkStbHeader(path);
    // stb_image would silently tone-map HDR data to 8 bits; refuse instead.
    if (stbi_is_hdr(path.c_str())) failFile(path.string(), "file holds Radiance HDR data; name it .hdr");
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<unsigned char, StbFree> data(stbi_load(path.c_str(), &width, &height, &channels, 3));
    if (!data) failFile(path.string(), "cannot decode image: " + stbReason());
    checkImageSize(path, width, height);
    return linearFromSrgb8(data.get(), width, height);
}

Image loadRadianceHdr(const std::filesystem::path& path) {
    checkStbHeader(path);
    // stbi_loadf would accept 8-bit files too, guessing a gamma; only real HDR is linear.
    if (!stbi_is_hdr(path.c_str())) failFile(path.string(), "not a Radiance HDR file");
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<float, StbFree> data(stbi_loadf(path.c_str(), &width, &height, &channels, 3));
    if (!data) failFile(path.string(), "cannot decode Radiance HDR image: " + stbReason());
    checkImageSize(path, width, height);

    Image image(width, height);
    const float* src = data.get();
    for (Rgb& px : image.pixels()) {
        px = Rgb(src[0], src[1], src[2]);
        src += 3;
    }
    checkImageFinite(path, image);
    return image;
}

}  // namespace

Image decodeImageBytes(std::span<const unsigned char> bytes, const std::string& label, ImageEncoding encoding) {
    // stb takes an int length; images of 2 GiB are far beyond the size limit anyway.
    if (bytes.empty() || bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        failFile(label, "cannot read image: " + std::to_string(bytes.size()) + " bytes");
    const auto length = static_cast<int>(bytes.size());
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels))
        failFile(label, "cannot read image: " + stbReason());
    checkImageSize(label, width, height);
    const auto pixels = static_cast<std::uintmax_t>(width) * static_cast<std::uintmax_t>(height);
    if (pixels > kMaxPixelsPerByte * bytes.size())
        failFile(label, "header claims " + std::to_string(width) + "x" + std::to_string(height) +
                            " pixels in " + std::to_string(bytes.size()) + " bytes: corrupt");
    if (stbi_is_hdr_from_memory(bytes.data(), length)) failFile(label, "holds Radiance HDR data, not an 8-bit image");
    std::unique_ptr<unsigned char, StbFree> data(stbi_load_from_memory(bytes.data(), length, &width, &height, &channels, 3));
    if (!data) failFile(label, "cannot decode image: " + stbReason());
    checkImageSize(label, width, height);
    return linearFromSrgb8(data.get(), width, height, encoding);
}

Image loadImageFile(const std::filesystem::path& path) {
    const ImageFormat format = formatOf(path);
    if (format == ImageFormat::Unsupported)
        failFile(path.string(), "unsupported image format '" + path.extension().string() +
                       "' (expected .png, .jpg, .jpeg, .bmp, .tga, .hdr or .exr)");
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) failFile(path.string(), "image file not found");
    if (!std::filesystem::is_regular_file(path, ec)) failFile(path.string(), "not a regular file");

    switch (format) {
        case ImageFormat::Srgb8: return loadSrgb8(path);
        case ImageFormat::RadianceHdr: return loadRadianceHdr(path);
        case ImageFormat::OpenExr: return readExrImage(path);
        case ImageFormat::Unsupported: break;
    }
    failFile(path.string(), "unsupported image format");
}

}  // namespace raycache
