#include "scene/ImageLoader.h"

#include <stb_image.h>
#include <tinyexr.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <system_error>

#include "core/ColorSpace.h"
#include "core/Errors.h"

namespace raycache {
namespace {

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

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
    throw InputError(InputLocation{.file = path.string()}, message);
}

void checkSize(const std::filesystem::path& path, int width, int height) {
    if (width <= 0 || height <= 0)
        fail(path, "image has zero size (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    if (width > maxImageSide || height > maxImageSide)
        fail(path, "image is " + std::to_string(width) + "x" + std::to_string(height) +
                       ", larger than the limit of " + std::to_string(maxImageSide) + " per side");
}

void checkFinite(const std::filesystem::path& path, const Image& image) {
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (!image.at(x, y).isFinite())
                fail(path, "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                               ") is not a finite number");
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
        fail(path, "cannot read image: " + stbReason());
    checkSize(path, width, height);
    // No format stb reads compresses pixels much better than deflate's
    // ~1032:1, so a header claiming far more pixels than that for its file's
    // bytes is corrupt: reject it before stb allocates and clears it all
    // (a 33-byte TGA claiming 16384x10752 took 14 s under ASan).
    constexpr std::uintmax_t kMaxPixelsPerByte = 1100;
    std::error_code error;
    const std::uintmax_t bytes = std::filesystem::file_size(path, error);
    const auto pixels = static_cast<std::uintmax_t>(width) * static_cast<std::uintmax_t>(height);
    if (!error && pixels > kMaxPixelsPerByte * bytes)
        fail(path, "header claims " + std::to_string(width) + "x" + std::to_string(height) + " pixels in a file of " +
                       std::to_string(bytes) + " bytes: corrupt");
}

Image loadSrgb8(const std::filesystem::path& path) {
    checkStbHeader(path);
    // stb_image would silently tone-map HDR data to 8 bits; refuse instead.
    if (stbi_is_hdr(path.c_str())) fail(path, "file holds Radiance HDR data; name it .hdr");
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<unsigned char, StbFree> data(stbi_load(path.c_str(), &width, &height, &channels, 3));
    if (!data) fail(path, "cannot decode image: " + stbReason());
    checkSize(path, width, height);

    std::array<float, 256> toLinear{};
    for (std::size_t i = 0; i < toLinear.size(); ++i)
        toLinear[i] = srgbToLinear(static_cast<float>(i) / 255.0f);

    Image image(width, height);
    const unsigned char* src = data.get();
    for (Rgb& px : image.pixels()) {
        px = Rgb(toLinear[src[0]], toLinear[src[1]], toLinear[src[2]]);
        src += 3;
    }
    return image;
}

Image loadRadianceHdr(const std::filesystem::path& path) {
    checkStbHeader(path);
    // stbi_loadf would accept 8-bit files too, guessing a gamma; only real HDR is linear.
    if (!stbi_is_hdr(path.c_str())) fail(path, "not a Radiance HDR file");
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<float, StbFree> data(stbi_loadf(path.c_str(), &width, &height, &channels, 3));
    if (!data) fail(path, "cannot decode Radiance HDR image: " + stbReason());
    checkSize(path, width, height);

    Image image(width, height);
    const float* src = data.get();
    for (Rgb& px : image.pixels()) {
        px = Rgb(src[0], src[1], src[2]);
        src += 3;
    }
    checkFinite(path, image);
    return image;
}

// LoadEXR allocates its result with malloc.
struct MallocFree {
    void operator()(void* p) const { std::free(p); }
};

// tinyexr reports errors through a heap string the caller must free.
std::string takeExrError(const char* err, int code) {
    std::string message = err ? err : "error code " + std::to_string(code);
    if (err) FreeEXRErrorMessage(err);
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
    return message;
}

// The "type" attribute, which tinyexr asserts on (aborting the process) when
// it contradicts the file's layout or names an unknown type (found by
// fuzzing, docs/testing.md). Read by hand before tinyexr sees the header,
// walking the attributes exactly as tinyexr 1.0.1's ParseEXRHeader does (names
// of any length, at most 1024 attributes, an empty value only for a string), so
// that no "type" it would see can be missed here; anything else malformed is
// left to tinyexr.
std::optional<std::string> exrTypeAttribute(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string file((std::istreambuf_iterator<char>(in)), {});
    constexpr std::size_t kHeaderStart = 8;      // magic number and version field
    constexpr std::size_t kMaxAttributes = 1024;  // TINYEXR_MAX_HEADER_ATTRIBUTES
    std::optional<std::string> result;            // the last "type" attribute, up to its first NUL
    std::size_t at = kHeaderStart;
    // One NUL-terminated string starting at `at`, or nothing if the file ends first.
    const auto readString = [&file, &at]() -> std::optional<std::string> {
        const std::size_t end = file.find('\0', at);
        if (end == std::string::npos) return std::nullopt;
        std::string text = file.substr(at, end - at);
        at = end + 1;
        return text;
    };
    for (std::size_t n = 0; n < kMaxAttributes && at < file.size() && file[at] != '\0'; ++n) {
        const std::optional<std::string> name = readString();
        const std::optional<std::string> type = name ? readString() : std::nullopt;
        if (!type || file.size() - at < sizeof(std::uint32_t)) break;
        std::uint32_t size = 0;  // little-endian, as the machines we build on
        std::memcpy(&size, file.data() + at, sizeof size);
        at += sizeof size;
        if ((size == 0 && *type != "string") || file.size() - at < size) break;
        if (*name == "type" && size > 0 && file[at] != '\0') {
            const std::string value = file.substr(at, size);
            result = std::string(value.c_str());
        }
        at += size;
    }
    return result;
}

void checkExrHeader(const std::filesystem::path& path) {
    EXRVersion version{};
    int code = ParseEXRVersionFromFile(&version, path.c_str());
    if (code != TINYEXR_SUCCESS) fail(path, "not an OpenEXR file (" + takeExrError(nullptr, code) + ")");
    // Only flat single-part scanline images are read. Environment maps and
    // textures do not need the rest, and Debian's tinyexr 1.0.1 crashes
    // (SEGV) on some corrupt ZIP-tiled files, which no check of ours could
    // rule out (tests/fuzz/findings/tinyexr-segv-zip-tiled.exr, docs/testing.md).
    if (version.multipart) fail(path, "multi-part EXR is not supported, save it as a single-part scanline image");
    if (version.non_image) fail(path, "deep EXR is not supported, save it as a flat scanline image");
    if (version.tiled) fail(path, "tiled EXR is not supported, save it as scanline");
    if (const std::optional<std::string> type = exrTypeAttribute(path); type && *type != "scanlineimage")
        fail(path, "OpenEXR header: type \"" + *type + "\", but the file is laid out as scanlineimage");
    EXRHeader header;
    InitEXRHeader(&header);
    const char* err = nullptr;
    code = ParseEXRHeaderFromFile(&header, &version, path.c_str(), &err);
    if (code != TINYEXR_SUCCESS) {
        FreeEXRHeader(&header);
        fail(path, "cannot read OpenEXR header: " + takeExrError(err, code));
    }
    // Widen before subtracting: a corrupt window can overflow int.
    const long long width = static_cast<long long>(header.data_window.max_x) - header.data_window.min_x + 1;
    const long long height = static_cast<long long>(header.data_window.max_y) - header.data_window.min_y + 1;
    // tinyexr 1.0.1 checks the bounds of a 32-bit integer (UINT) channel's
    // data one byte at a time but reads four, past the end of a short block
    // (a heap over-read found by fuzzing, docs/testing.md). Colour is never
    // stored as integers, and tinyexr decodes every channel, so refuse them.
    std::optional<std::string> integerChannel;
    for (int c = 0; c < header.num_channels && !integerChannel; ++c)
        if (header.pixel_types[c] == TINYEXR_PIXELTYPE_UINT) integerChannel = std::string(header.channels[c].name);
    // tinyexr 1.0.1's PIZ decoder copies past the end of a corrupt block (a
    // heap over-read found by fuzzing, docs/testing.md); ZIP, RLE and
    // uncompressed files are read.
    const bool piz = header.compression_type == TINYEXR_COMPRESSIONTYPE_PIZ;
    FreeEXRHeader(&header);
    if (piz) fail(path, "PIZ-compressed EXR is not supported, save it with ZIP compression (or none)");
    if (integerChannel)
        fail(path, "OpenEXR channel \"" + *integerChannel +
                       "\" holds 32-bit integers, which are not supported; save the image with half or float "
                       "channels only");
    checkSize(path, static_cast<int>(std::clamp(width, -1LL, maxImageSide + 1LL)),
              static_cast<int>(std::clamp(height, -1LL, maxImageSide + 1LL)));
}

Image loadOpenExr(const std::filesystem::path& path) {
    checkExrHeader(path);
    float* rgba = nullptr;
    int width = 0, height = 0;
    const char* err = nullptr;
    const int code = LoadEXR(&rgba, &width, &height, path.c_str(), &err);
    std::unique_ptr<float, MallocFree> data(rgba);
    if (code != TINYEXR_SUCCESS || !data) fail(path, "cannot decode OpenEXR image: " + takeExrError(err, code));
    checkSize(path, width, height);

    Image image(width, height);
    const float* src = data.get();
    for (Rgb& px : image.pixels()) {
        px = Rgb(src[0], src[1], src[2]);
        src += 4;
    }
    checkFinite(path, image);
    return image;
}

}  // namespace

Image loadImageFile(const std::filesystem::path& path) {
    const ImageFormat format = formatOf(path);
    if (format == ImageFormat::Unsupported)
        fail(path, "unsupported image format '" + path.extension().string() +
                       "' (expected .png, .jpg, .jpeg, .bmp, .tga, .hdr or .exr)");
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(path, "image file not found");
    if (!std::filesystem::is_regular_file(path, ec)) fail(path, "not a regular file");

    switch (format) {
        case ImageFormat::Srgb8: return loadSrgb8(path);
        case ImageFormat::RadianceHdr: return loadRadianceHdr(path);
        case ImageFormat::OpenExr: return loadOpenExr(path);
        case ImageFormat::Unsupported: break;
    }
    fail(path, "unsupported image format");
}

}  // namespace raycache
