#include "scene/ExrImageReader.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <openexr.h>

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <fstream>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

#include "core/Errors.h"
#include "scene/ImageFileChecks.h"

namespace raycache {
namespace {

// OpenEXR's messages may hold line breaks; our errors are one line.
std::string oneLine(std::string text) {
    for (char& c : text)
        if (std::iscntrl(static_cast<unsigned char>(c))) c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// A channel name from the file as printable ASCII: a corrupt one may hold any byte.
std::string printableName(const char* name) {
    std::string text(name);
    for (char& c : text)
        if (c < ' ' || c > '~') c = '?';
    return text;
}

// The channels whose values become the image's colour: three names, or one
// name three times for grey.
struct ColourChannels {
    std::string r, g, b;
    bool grey() const { return r == g; }
};

// What the reader needs of the first part's header.
struct ExrLayout {
    int minX = 0, minY = 0, maxX = 0, maxY = 0;  // the data window, inclusive
    int bandRows = 1;                            // rows read at a time: one block's
    ColourChannels colour;
};

// The C core's error callback: keeps the first message (the most specific)
// for our one error line, instead of the core's default print to stderr.
void keepFirstMessage(exr_const_context_t context, exr_result_t code, const char* message) {
    void* user = nullptr;
    if (exr_get_user_data(context, &user) != EXR_ERR_SUCCESS || !user) return;
    auto& kept = *static_cast<std::string*>(user);
    if (kept.empty()) kept = message ? message : exr_get_default_error_message(code);
}

struct FinishContext {
    void operator()(exr_context_t context) const { exr_finish(&context); }
};
using ContextHandle = std::unique_ptr<std::remove_pointer_t<exr_context_t>, FinishContext>;

std::string channelNames(const exr_attr_chlist_t& channels) {
    constexpr int kListed = 8;
    std::string names;
    for (int i = 0; i < channels.num_channels && i < kListed; ++i)
        names += (i ? ", " : "") + printableName(channels.entries[i].name.str);
    if (channels.num_channels > kListed) names += ", ...";
    return names;
}

const exr_attr_chlist_entry_t* findChannel(const exr_attr_chlist_t& channels, const char* name) {
    for (int i = 0; i < channels.num_channels; ++i)
        if (std::string(channels.entries[i].name.str) == name) return &channels.entries[i];
    return nullptr;
}

// R, G and B; else Y or a lone channel as grey (tinyexr's rule before, which
// took a lone channel of any name as grey, kept).
ColourChannels chooseColour(const std::filesystem::path& path, const exr_attr_chlist_t& channels) {
    std::vector<const exr_attr_chlist_entry_t*> used;
    if (findChannel(channels, "R") && findChannel(channels, "G") && findChannel(channels, "B"))
        used = {findChannel(channels, "R"), findChannel(channels, "G"), findChannel(channels, "B")};
    else if (const exr_attr_chlist_entry_t* y = findChannel(channels, "Y"))
        used = {y, y, y};
    else if (channels.num_channels == 1)
        used = {&channels.entries[0], &channels.entries[0], &channels.entries[0]};
    else
        failFile(path.string(), "OpenEXR image has the channels " + channelNames(channels) +
                       ": expected R, G and B, or Y (or a single channel) for grey");
    for (const exr_attr_chlist_entry_t* c : used) {
        const std::string name = printableName(c->name.str);
        // Colour is never stored as integers; reading them as float would
        // make an id or a count look like radiance.
        if (c->pixel_type == EXR_PIXEL_UINT)
            failFile(path.string(), "OpenEXR channel \"" + name +
                           "\" holds 32-bit integers, which are not supported; save the image with half or float "
                           "channels only");
        if (c->x_sampling != 1 || c->y_sampling != 1)
            failFile(path.string(), "OpenEXR channel \"" + name + "\" is subsampled (" + std::to_string(c->x_sampling) + "x" +
                           std::to_string(c->y_sampling) + "), which is not supported; save it at full resolution");
    }
    return {used[0]->name.str, used[1]->name.str, used[2]->name.str};
}

// A NUL-terminated string of at most 255 bytes (a name in an OpenEXR header).
std::optional<std::string> readName(std::istream& in) {
    std::string name;
    for (char c = 0; in.get(c) && c != '\0';)
        if (name.size() < 255)
            name += c;
        else
            return std::nullopt;
    if (!in) return std::nullopt;
    return name;
}

// OpenEXR 3.1's C++ header reader reads a channel list up to its terminating
// empty name, whatever size the attribute declares; the core reads by the
// declared size. Where the two ends differ, the C++ reader goes on out of step
// and takes later bytes for an attribute's size, allocating what they claim
// (1.8 GB for a 2 KiB file, found by fuzzing, docs/testing.md finding 13).
// Checks that each of the `parts` headers' channel lists ends, terminator
// included, exactly at its declared size; the core has read the same headers,
// so every size lies within the file.
bool channelListsEndWhereTheySay(const std::filesystem::path& path, int parts) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(8);  // magic number and version field
    for (int part = 0; part < parts; ++part) {
        while (true) {
            const std::optional<std::string> name = readName(in);
            if (!name) return false;
            if (name->empty()) break;  // the end of this part's header
            const std::optional<std::string> type = readName(in);
            std::uint32_t size = 0;  // little-endian, as the machines we build on
            if (!type || !in.read(reinterpret_cast<char*>(&size), sizeof size)) return false;
            const std::streamoff end = static_cast<std::streamoff>(in.tellg()) + size;
            if (*type == "chlist") {
                std::optional<std::string> channel = readName(in);
                for (; channel && !channel->empty(); channel = readName(in))
                    in.seekg(16, std::ios::cur);  // type, linearity, reserved, x and y sampling
                if (!channel || in.tellg() != end) return false;
            }
            in.seekg(end);
        }
    }
    return true;
}

// Reads the header through OpenEXR's C core and refuses, before the C++
// library opens the file, what would make that library allocate far more than
// the file can hold. The core checks every attribute's size against the file
// before allocating for it, where the C++ header reader of OpenEXR 3.1
// allocates and fills whatever size a corrupt attribute claims (up to 2 GiB
// for a string); and the core allocates nothing for the pixels.
ExrLayout readLayout(const std::filesystem::path& path) {
    std::string coreMessage;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = &keepFirstMessage;
    init.user_data = &coreMessage;
    exr_context_t opened = nullptr;
    const exr_result_t started = exr_start_read(&opened, path.c_str(), &init);
    const ContextHandle context(opened);
    // The core reports a malformed attribute and, unless told to be strict,
    // reads on past it; the C++ library would allocate what it claims (1.6 GB
    // in a 2 KiB file, found by fuzzing, docs/testing.md finding 12).
    // Strict mode would also refuse names of 32-255 bytes without the
    // long-names flag, which the C++ library reads; so any report refuses.
    if (started != EXR_ERR_SUCCESS || !coreMessage.empty())
        failFile(path.string(), "cannot read OpenEXR header: " +
                       oneLine(coreMessage.empty() ? exr_get_default_error_message(started) : coreMessage));
    const auto check = [&](exr_result_t result) {
        if (result == EXR_ERR_SUCCESS) return;
        if (coreMessage.empty()) coreMessage = exr_get_default_error_message(result);
        failFile(path.string(), "cannot read OpenEXR header: " + oneLine(coreMessage));
    };

    int parts = 0;
    check(exr_get_count(opened, &parts));
    exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
    check(exr_get_storage(opened, 0, &storage));
    if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
        failFile(path.string(), "deep EXR is not supported, save the image flat");
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) failFile(path.string(), "OpenEXR part of unknown type");

    exr_attr_box2i_t window{};
    check(exr_get_data_window(opened, 0, &window));
    // Widened before subtracting: a corrupt window can overflow int.
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    checkImageSize(path, width, height);

    // Every part's table of chunk offsets (8 bytes each) must be in the file;
    // OpenEXR allocates each table before reading it.
    std::uint64_t chunks = 0;
    for (int part = 0; part < parts; ++part) {
        int32_t count = 0;
        check(exr_get_chunk_count(opened, part, &count));
        chunks += static_cast<std::uint64_t>(std::max(count, 0));
    }
    std::error_code sizeError;
    const std::uintmax_t fileBytes = std::filesystem::file_size(path, sizeError);
    if (!sizeError && chunks * 8 > fileBytes)
        failFile(path.string(), "OpenEXR file of " + std::to_string(fileBytes) + " bytes is too short for the offsets of its " +
                       std::to_string(chunks) + " blocks: truncated or corrupt");

    if (!channelListsEndWhereTheySay(path, parts))
        failFile(path.string(), "OpenEXR channel list does not end where its size says: corrupt");

    const exr_attr_chlist_t* channels = nullptr;
    check(exr_get_channels(opened, 0, &channels));
    if (!channels || channels->num_channels < 1) failFile(path.string(), "OpenEXR image has no channels");
    ExrLayout layout{.minX = window.min.x, .minY = window.min.y, .maxX = window.max.x, .maxY = window.max.y};
    layout.colour = chooseColour(path, *channels);

    // The bytes OpenEXR buffers: one block of every channel, unpacked, and
    // for tiled files a row of tiles of the three float channels we read.
    std::uint64_t bytesPerPixel = 0;
    for (int i = 0; i < channels->num_channels; ++i)
        bytesPerPixel += channels->entries[i].pixel_type == EXR_PIXEL_HALF ? 2 : 4;
    std::uint64_t blockBytes = 0;
    if (storage == EXR_STORAGE_TILED) {
        uint32_t tileWidth = 0, tileHeight = 0;
        exr_tile_level_mode_t levels{};
        exr_tile_round_mode_t rounding{};
        check(exr_get_tile_descriptor(opened, 0, &tileWidth, &tileHeight, &levels, &rounding));
        blockBytes = std::max<std::uint64_t>(std::uint64_t{tileWidth} * tileHeight * bytesPerPixel,
                                             static_cast<std::uint64_t>(width) * tileHeight * 3 * sizeof(float));
        layout.bandRows = static_cast<int>(std::clamp<long long>(tileHeight, 1, height));
    } else {
        int32_t rows = 0;
        check(exr_get_scanlines_per_chunk(opened, 0, &rows));
        blockBytes = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(std::max(rows, 1)) * bytesPerPixel;
        layout.bandRows = static_cast<int>(std::clamp<long long>(rows, 1, height));
    }
    if (blockBytes > maxExrBlockBytes)
        failFile(path.string(), "OpenEXR blocks of " + std::to_string(blockBytes >> 20) + " MiB, more than the limit of " +
                       std::to_string(maxExrBlockBytes >> 20) +
                       " MiB: corrupt, or save the image with smaller tiles or fewer channels");
    return layout;
}

// Decodes band after band of rows, so that memory grows only with pixels
// actually decoded: a small corrupt file claiming a large image fails at its
// first missing block, having allocated one band.
Image decode(const std::filesystem::path& path, const ExrLayout& layout) {
    Imf::InputFile file(path.c_str());
    // The limits were checked on the core's reading of the header; the C++
    // library's must agree (both refuse a required attribute given twice).
    const Imath::Box2i window = file.header().dataWindow();
    const Imf::ChannelList& channels = file.header().channels();
    if (window.min.x != layout.minX || window.min.y != layout.minY || window.max.x != layout.maxX ||
        window.max.y != layout.maxY || !channels.findChannel(layout.colour.r) ||
        !channels.findChannel(layout.colour.g) || !channels.findChannel(layout.colour.b))
        failFile(path.string(), "OpenEXR's two readings of the header differ: corrupt");

    const int width = layout.maxX - layout.minX + 1;
    const int height = layout.maxY - layout.minY + 1;
    const std::size_t total = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<Rgb> pixels;
    std::vector<Rgb> band;
    for (long long y0 = layout.minY; y0 <= layout.maxY; y0 += layout.bandRows) {
        const int first = static_cast<int>(y0);
        const int last = static_cast<int>(std::min<long long>(y0 + layout.bandRows - 1, layout.maxY));
        band.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(last - first + 1), Rgb());
        const Imath::Box2i rows({layout.minX, first}, {layout.maxX, last});
        const auto slice = [&](float Rgb::*component) {
            return Imf::Slice::Make(Imf::FLOAT, &(band.front().*component), rows, sizeof(Rgb), sizeof(Rgb) * width);
        };
        Imf::FrameBuffer frame;
        frame.insert(layout.colour.r, slice(&Rgb::r));
        if (!layout.colour.grey()) {
            frame.insert(layout.colour.g, slice(&Rgb::g));
            frame.insert(layout.colour.b, slice(&Rgb::b));
        }
        file.setFrameBuffer(frame);
        file.readPixels(first, last);
        if (layout.colour.grey())
            for (Rgb& px : band) px.g = px.b = px.r;
        // Grown by doubling up to the whole image, never past it.
        if (pixels.capacity() < pixels.size() + band.size())
            pixels.reserve(std::min(total, std::max(pixels.size() + band.size(), 2 * pixels.capacity())));
        pixels.insert(pixels.end(), band.begin(), band.end());
    }
    return Image(width, height, std::move(pixels));
}

}  // namespace

Image readExrImage(const std::filesystem::path& path) {
    const ExrLayout layout = readLayout(path);
    Image image;
    try {
        image = decode(path, layout);
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        // OpenEXR reports corrupt data by throwing (Iex::BaseExc, a std::exception).
        failFile(path.string(), "cannot decode OpenEXR image: " + oneLine(e.what()));
    }
    checkImageFinite(path, image);
    return image;
}

}  // namespace raycache
