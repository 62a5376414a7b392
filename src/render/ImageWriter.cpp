#include "render/ImageWriter.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <exception>
#include <string>
#include <system_error>
#include <vector>

#include "core/AtomicFile.h"
#include "core/ColorSpace.h"
#include "core/Errors.h"

namespace raycache {
namespace {

std::string lowerImageExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

// Returns an error message, empty on success.
std::string savePng(const Image& image, const DisplayTransform& display, const std::filesystem::path& file) {
    std::vector<unsigned char> bytes;
    bytes.reserve(image.pixels().size() * 3);
    for (const Rgb& film : image.pixels()) {
        const Rgb px = display.identity() ? film : display(film);
        bytes.push_back(linearToSrgb8(px.r));
        bytes.push_back(linearToSrgb8(px.g));
        bytes.push_back(linearToSrgb8(px.b));
    }
    if (!stbi_write_png(file.c_str(), image.width(), image.height(), 3, bytes.data(), image.width() * 3))
        return "cannot write PNG data";
    return {};
}

// Returns an error message, empty on success. Float channels R, G, B, ZIP
// compressed (blocks of 16 scanlines): the pixel values written are the
// image's, bit for bit.
std::string saveExr(const Image& image, const std::filesystem::path& file) {
    try {
        Imf::Header header(image.width(), image.height());
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
        // Our pixels are interleaved RGB; a slice reads one component of each.
        const char* base = reinterpret_cast<const char*>(image.pixels().data());
        const std::size_t row = sizeof(Rgb) * static_cast<std::size_t>(image.width());
        Imf::FrameBuffer frame;
        frame.insert("R", Imf::Slice(Imf::FLOAT, const_cast<char*>(base + offsetof(Rgb, r)), sizeof(Rgb), row));
        frame.insert("G", Imf::Slice(Imf::FLOAT, const_cast<char*>(base + offsetof(Rgb, g)), sizeof(Rgb), row));
        frame.insert("B", Imf::Slice(Imf::FLOAT, const_cast<char*>(base + offsetof(Rgb, b)), sizeof(Rgb), row));
        // The file is complete once `out` is destroyed (it writes the offsets
        // of its blocks then), before writeFileAtomically renames it.
        Imf::OutputFile out(file.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(image.height());
    } catch (const std::exception& e) {
        // OpenEXR reports failures by throwing (Iex::BaseExc, a std::exception).
        return e.what();
    }
    return {};
}

}  // namespace

bool isSupportedImageExtension(const std::filesystem::path& path) {
    const std::string ext = lowerImageExtension(path);
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

void writeImage(const Image& image, const std::filesystem::path& path, const DisplaySettings& display) {
    checkWritableImagePath(path);
    if (image.empty())
        throw RuntimeError("cannot write " + path.string() + ": the image is empty");

    const bool png = lowerImageExtension(path) == ".png";
    writeFileAtomically(path, [&](const std::filesystem::path& temp) {
        const std::string error = png ? savePng(image, DisplayTransform(display), temp) : saveExr(image, temp);
        if (!error.empty()) throw RuntimeError(error);
    });
}

}  // namespace raycache
