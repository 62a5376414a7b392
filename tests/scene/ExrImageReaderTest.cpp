// The EXR reader against files written by OpenEXR's own writer classes: every
// compression, scanline and tiled, half and float, multi-part, a data window
// away from the origin, grey, and what it refuses.
#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineOutputFile.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfTileDescription.h>
#include <ImfTiledOutputFile.h>
#include <ImfTiledOutputPart.h>
#include <gtest/gtest.h>

#include "ImageFileRefusal.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "TempDir.h"
#include "core/Errors.h"
#include "scene/ExrImageReader.h"
#include "scene/ImageLoader.h"

namespace raycache {
namespace {

// Channel `c` of pixel (x, y), counted from the data window's corner: a
// gradient (kind to the lossy compressions), exact in half for the small
// pictures (below 128 = 2048 sixteenths).
float sample(int c, int x, int y) {
    return static_cast<float>(16 + c * 64 + y * 8 + x) / 16.0f;
}

// A picture to write: float planes, one per channel, over a data window.
struct ExrPicture {
    ExrPicture(Imath::Box2i window_, std::vector<std::string> channels_)
        : window(window_), channels(std::move(channels_)) {
        for (std::size_t c = 0; c < channels.size(); ++c) {
            planes.emplace_back();
            for (int y = 0; y < height(); ++y)
                for (int x = 0; x < width(); ++x) planes.back().push_back(sample(static_cast<int>(c), x, y));
        }
    }
    int width() const { return window.max.x - window.min.x + 1; }
    int height() const { return window.max.y - window.min.y + 1; }
    float value(const std::string& channel, int x, int y) const {
        for (std::size_t c = 0; c < channels.size(); ++c)
            if (channels[c] == channel) return planes[c][static_cast<std::size_t>(y * width() + x)];
        ADD_FAILURE() << "no channel " << channel;
        return 0.0f;
    }
    // Display window fixed, so that a data window elsewhere is really offset.
    Imf::Header header(Imf::PixelType type, Imf::Compression compression) const {
        Imf::Header h(Imath::Box2i({0, 0}, {63, 63}), window);
        h.compression() = compression;
        for (const std::string& name : channels) h.channels().insert(name, Imf::Channel(type));
        return h;
    }
    // Slices of the file's type (OpenEXR's writer does not convert).
    Imf::FrameBuffer frameBuffer(Imf::PixelType type) {
        if (type == Imf::HALF && halfPlanes.empty())
            for (const auto& plane : planes) halfPlanes.emplace_back(plane.begin(), plane.end());
        Imf::FrameBuffer frame;
        for (std::size_t c = 0; c < channels.size(); ++c)
            frame.insert(channels[c], type == Imf::HALF ? Imf::Slice::Make(Imf::HALF, halfPlanes[c].data(), window)
                                                        : Imf::Slice::Make(Imf::FLOAT, planes[c].data(), window));
        return frame;
    }

    Imath::Box2i window;
    std::vector<std::string> channels;
    std::vector<std::vector<float>> planes;
    std::vector<std::vector<half>> halfPlanes;
};

const Imath::Box2i kWindow({0, 0}, {6, 4});     // 7x5: partial 4x4 tiles on two edges
const Imath::Box2i kOffset({-3, 10}, {3, 14});  // the same size elsewhere
const std::vector<std::string> kRgb = {"R", "G", "B"};

void writeScanline(const std::filesystem::path& path, ExrPicture& picture, Imf::PixelType type,
                   Imf::Compression compression) {
    Imf::OutputFile out(path.c_str(), picture.header(type, compression));
    out.setFrameBuffer(picture.frameBuffer(type));
    out.writePixels(picture.height());
}

void writeTiled(const std::filesystem::path& path, ExrPicture& picture, Imf::PixelType type,
                Imf::Compression compression, Imf::LevelMode levels = Imf::ONE_LEVEL) {
    Imf::Header header = picture.header(type, compression);
    header.setTileDescription(Imf::TileDescription(4, 4, levels));
    Imf::TiledOutputFile out(path.c_str(), header);
    // Every level from the same planes: coarser levels cover a corner of them.
    out.setFrameBuffer(picture.frameBuffer(type));
    for (int ly = 0; ly < out.numYLevels(); ++ly)
        for (int lx = 0; lx < out.numXLevels(); ++lx)
            if (levels == Imf::RIPMAP_LEVELS || lx == ly)
                out.writeTiles(0, out.numXTiles(lx) - 1, 0, out.numYTiles(ly) - 1, lx, ly);
}

// The loaded image against the picture's R, G, B (or `grey` in all three).
void expectPicture(const Image& image, const ExrPicture& picture, float tolerance = 0.0f,
                   const std::string& grey = "") {
    ASSERT_EQ(image.width(), picture.width());
    ASSERT_EQ(image.height(), picture.height());
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const Rgb want = grey.empty()
                                 ? Rgb(picture.value("R", x, y), picture.value("G", x, y), picture.value("B", x, y))
                                 : Rgb(picture.value(grey, x, y));
            const Rgb got = image.at(x, y);
            if (tolerance == 0.0f) {
                ASSERT_EQ(got, want) << "pixel " << x << ", " << y;
            } else {
                ASSERT_NEAR(got.r, want.r, tolerance) << "pixel " << x << ", " << y;
                ASSERT_NEAR(got.g, want.g, tolerance) << "pixel " << x << ", " << y;
                ASSERT_NEAR(got.b, want.b, tolerance) << "pixel " << x << ", " << y;
            }
        }
}

std::string readBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// Overwrites the 32-bit little-endian integer `field` ints into the value of
// the header attribute `name` of type `type` (-1: the attribute's size field).
void patchAttribute(const std::filesystem::path& path, const std::string& name, const std::string& type, int field,
                    std::int32_t value) {
    std::string bytes = readBytes(path);
    const std::string key = name + '\0' + type + '\0';
    const std::size_t at = bytes.find(key);
    ASSERT_NE(at, std::string::npos) << name;
    std::memcpy(bytes.data() + at + key.size() + 4 + 4 * field, &value, sizeof value);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

struct CompressionCase {
    Imf::Compression compression;
    const char* name;
};
const CompressionCase kCompressions[] = {
    {Imf::NO_COMPRESSION, "none"},   {Imf::RLE_COMPRESSION, "rle"},   {Imf::ZIPS_COMPRESSION, "zips"},
    {Imf::ZIP_COMPRESSION, "zip"},   {Imf::PIZ_COMPRESSION, "piz"},   {Imf::PXR24_COMPRESSION, "pxr24"},
    {Imf::B44_COMPRESSION, "b44"},   {Imf::B44A_COMPRESSION, "b44a"}, {Imf::DWAA_COMPRESSION, "dwaa"},
    {Imf::DWAB_COMPRESSION, "dwab"},
};

// Lossless unless the compression is lossy for that pixel type: PXR24 rounds
// float to 24 bits, B44 packs half (and leaves float alone), DWA is lossy for
// colour of either type.
bool exact(Imf::Compression compression, Imf::PixelType type) {
    switch (compression) {
        case Imf::PXR24_COMPRESSION:
            return type == Imf::HALF;
        case Imf::B44_COMPRESSION:
        case Imf::B44A_COMPRESSION:
            return type == Imf::FLOAT;
        case Imf::DWAA_COMPRESSION:
        case Imf::DWAB_COMPRESSION:
            return false;
        default:
            return true;
    }
}

TEST(ExrImageReader, EveryCompressionScanlineAndTiledHalfAndFloat) {
    TempDir dir;
    for (const CompressionCase& c : kCompressions)
        for (const Imf::PixelType type : {Imf::HALF, Imf::FLOAT})
            for (const bool tiled : {false, true}) {
                const std::string name = std::string(c.name) + (type == Imf::HALF ? "-half" : "-float") +
                                         (tiled ? "-tiled" : "-scanline") + ".exr";
                SCOPED_TRACE(name);
                const auto path = dir.path() / name;
                ExrPicture picture(tiled ? kWindow : kOffset, kRgb);
                if (tiled)
                    writeTiled(path, picture, type, c.compression);
                else
                    writeScanline(path, picture, type, c.compression);
                // The lossy ones within a few percent of values from 1 to 13.
                expectPicture(loadImageFile(path), picture, exact(c.compression, type) ? 0.0f : 0.25f);
            }
}

// Bigger than one block of every compression (DWAB's is 256 rows), with a
// data window away from the origin: blocks, bands and offsets line up.
TEST(ExrImageReader, LargerImagesSpanManyBlocks) {
    TempDir dir;
    ExrPicture picture(Imath::Box2i({5, -300}, {44, 299}), kRgb);  // 40x600
    for (const Imf::Compression compression : {Imf::ZIP_COMPRESSION, Imf::PIZ_COMPRESSION, Imf::DWAB_COMPRESSION}) {
        const auto path = dir.path() / ("large-" + std::to_string(compression) + ".exr");
        writeScanline(path, picture, Imf::FLOAT, compression);
        // The gradient reaches 16 + 128 + 599 * 8 + 39 sixteenths (about 311).
        expectPicture(loadImageFile(path), picture, compression == Imf::DWAB_COMPRESSION ? 2.0f : 0.0f);
    }
    const auto tiled = dir.path() / "large-tiled.exr";
    writeTiled(tiled, picture, Imf::FLOAT, Imf::ZIP_COMPRESSION);
    expectPicture(loadImageFile(tiled), picture);
}

TEST(ExrImageReader, DataWindowAwayFromTheOriginIsTheImage) {
    TempDir dir;
    const auto path = dir.path() / "offset.exr";
    ExrPicture picture(Imath::Box2i({10, 20}, {16, 24}), kRgb);
    writeScanline(path, picture, Imf::FLOAT, Imf::ZIP_COMPRESSION);
    const Image image = loadImageFile(path);
    expectPicture(image, picture);
    EXPECT_EQ(image.at(0, 0), Rgb(sample(0, 0, 0), sample(1, 0, 0), sample(2, 0, 0)));  // data window (10, 20)
}

TEST(ExrImageReader, MipmappedAndRipmappedFilesGiveTheirFullResolutionLevel) {
    TempDir dir;
    for (const Imf::LevelMode levels : {Imf::MIPMAP_LEVELS, Imf::RIPMAP_LEVELS}) {
        const auto path = dir.path() / ("levels-" + std::to_string(levels) + ".exr");
        ExrPicture picture(kWindow, kRgb);
        writeTiled(path, picture, Imf::HALF, Imf::PIZ_COMPRESSION, levels);
        expectPicture(loadImageFile(path), picture);
    }
}

// The first part is read, whatever follows it.
TEST(ExrImageReader, MultipartFileGivesItsFirstPart) {
    TempDir dir;
    const auto path = dir.path() / "multipart.exr";
    ExrPicture beauty(kOffset, kRgb);
    ExrPicture depth(kWindow, {"Z"});
    Imf::Header headers[2] = {beauty.header(Imf::HALF, Imf::PIZ_COMPRESSION),
                              depth.header(Imf::FLOAT, Imf::ZIP_COMPRESSION)};
    headers[0].setName("beauty");
    headers[0].setType(Imf::TILEDIMAGE);
    headers[0].setTileDescription(Imf::TileDescription(4, 4));
    headers[1].setName("depth");
    headers[1].setType(Imf::SCANLINEIMAGE);
    {
        Imf::MultiPartOutputFile out(path.c_str(), headers, 2);
        Imf::TiledOutputPart first(out, 0);
        first.setFrameBuffer(beauty.frameBuffer(Imf::HALF));
        first.writeTiles(0, first.numXTiles() - 1, 0, first.numYTiles() - 1);
        Imf::OutputPart second(out, 1);
        second.setFrameBuffer(depth.frameBuffer(Imf::FLOAT));
        second.writePixels(depth.height());
    }
    expectPicture(loadImageFile(path), beauty);
}

TEST(ExrImageReader, GreyFromYOrALoneChannel) {
    TempDir dir;
    for (const auto& channels : std::vector<std::vector<std::string>>{{"Y"}, {"A", "Y"}, {"Z"}}) {
        const auto path = dir.path() / (channels.back() + std::to_string(channels.size()) + ".exr");
        ExrPicture picture(kWindow, channels);
        writeScanline(path, picture, Imf::HALF, Imf::ZIP_COMPRESSION);
        expectPicture(loadImageFile(path), picture, 0.0f, channels.back());
    }
}

// Alpha, layers and integer channels beside the colour do not matter.
TEST(ExrImageReader, OtherChannelsBesideColourAreIgnored) {
    TempDir dir;
    const auto path = dir.path() / "extra.exr";
    ExrPicture picture(kWindow, {"A", "B", "G", "R", "diffuse.R"});
    Imf::Header header = picture.header(Imf::FLOAT, Imf::ZIP_COMPRESSION);
    header.channels().insert("id", Imf::Channel(Imf::UINT));
    std::vector<unsigned> ids(picture.planes[0].size(), 7u);
    Imf::FrameBuffer frame = picture.frameBuffer(Imf::FLOAT);
    frame.insert("id", Imf::Slice::Make(Imf::UINT, ids.data(), kWindow));
    {
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(picture.height());
    }
    expectPicture(loadImageFile(path), picture);
}

TEST(ExrImageReader, WithoutColourChannelsIsOneError) {
    TempDir dir;
    const auto path = dir.path() / "rg.exr";
    ExrPicture picture(kWindow, {"G", "R"});
    writeScanline(path, picture, Imf::HALF, Imf::ZIP_COMPRESSION);
    expectImageFileRefused(path, "OpenEXR image has the channels G, R: expected R, G and B, or Y");
}

TEST(ExrImageReader, IntegerColourIsOneError) {
    TempDir dir;
    const auto path = dir.path() / "uint.exr";
    ExrPicture picture(kWindow, {"Y"});
    Imf::Header header(kWindow.max.x + 1, kWindow.max.y + 1);
    header.channels().insert("Y", Imf::Channel(Imf::UINT));
    std::vector<unsigned> values(picture.planes[0].size(), 3u);
    Imf::FrameBuffer frame;
    frame.insert("Y", Imf::Slice::Make(Imf::UINT, values.data(), kWindow));
    {
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(picture.height());
    }
    expectImageFileRefused(path, "OpenEXR channel \"Y\" holds 32-bit integers, which are not supported");
}

TEST(ExrImageReader, SubsampledColourIsOneError) {
    TempDir dir;
    const auto path = dir.path() / "subsampled.exr";
    const Imath::Box2i window({0, 0}, {7, 5});
    ExrPicture picture(window, kRgb);
    Imf::Header header = picture.header(Imf::HALF, Imf::ZIP_COMPRESSION);
    header.channels()["R"].xSampling = 2;
    header.channels()["R"].ySampling = 2;
    Imf::FrameBuffer frame = picture.frameBuffer(Imf::HALF);
    frame["R"] = Imf::Slice::Make(Imf::HALF, picture.halfPlanes[0].data(), window, 0, 0, 2, 2);
    {
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(picture.height());
    }
    expectImageFileRefused(path, "OpenEXR channel \"R\" is subsampled (2x2), which is not supported");
}

TEST(ExrImageReader, DeepFileIsOneError) {
    TempDir dir;
    const auto path = dir.path() / "deep.exr";
    const int width = 4, height = 3;
    Imf::Header header(width, height);
    header.setType(Imf::DEEPSCANLINE);
    header.compression() = Imf::ZIPS_COMPRESSION;
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    std::vector<unsigned> counts(width * height, 1u);
    std::vector<float> values(width * height, 0.5f);
    std::vector<float*> samples;
    for (float& v : values) samples.push_back(&v);
    Imf::DeepFrameBuffer frame;
    frame.insertSampleCountSlice(
        Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()), sizeof(unsigned), sizeof(unsigned) * width));
    frame.insert("R", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(samples.data()), sizeof(float*),
                                     sizeof(float*) * width, sizeof(float)));
    {
        Imf::DeepScanLineOutputFile out(path.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(height);
    }
    expectImageFileRefused(path, "deep EXR is not supported");
}

// A header claiming tiles far larger than a texture needs is refused before
// OpenEXR allocates buffers for them (16384² half RGB tiles: 1.5 GiB each).
TEST(ExrImageReader, HugeTilesAreRefusedFromTheHeader) {
    TempDir dir;
    const auto path = dir.path() / "huge-tiles.exr";
    ExrPicture picture(kWindow, kRgb);
    writeTiled(path, picture, Imf::HALF, Imf::ZIP_COMPRESSION);
    patchAttribute(path, "tiles", "tiledesc", 0, 16384);
    patchAttribute(path, "tiles", "tiledesc", 1, 16384);
    expectImageFileRefused(path, "OpenEXR blocks of 1536 MiB, more than the limit of 256 MiB");
}

// A small file whose data window claims 16384x16384: its 1024 block offsets
// alone would take 8 KiB.
TEST(ExrImageReader, WindowFarLargerThanTheFileIsRefusedFromTheHeader) {
    TempDir dir;
    const auto path = dir.path() / "huge-window.exr";
    ExrPicture picture(kWindow, kRgb);
    writeScanline(path, picture, Imf::HALF, Imf::ZIP_COMPRESSION);
    patchAttribute(path, "dataWindow", "box2i", 2, 16383);
    patchAttribute(path, "dataWindow", "box2i", 3, 16383);
    expectImageFileRefused(path, "is too short for the offsets of its 1024 blocks");
}

// OpenEXR's C++ header reader allocates whatever size an attribute claims.
// Found by fuzzing (docs/testing.md, findings 12 and 13): an attribute whose
// size the core reports as larger than the file, and a channel list declaring
// fewer bytes than its entries take, after which the C++ reader, reading the
// list to its end, takes the next attribute's name for a size. Both are
// refused before the C++ library opens the file.
TEST(ExrImageReader, HeadersTheCxxReaderWouldMisreadAreRefused) {
    const auto findings = std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings";
    expectImageFileRefused(findings / "openexr-huge-attribute-after-a-bad-one.exr", "Invalid size 1677721600");
    expectImageFileRefused(findings / "openexr-channel-list-shorter-than-its-entries.exr",
                               "OpenEXR channel list does not end where its size says");
    TempDir dir;
    for (const int change : {-1, +1}) {
        const auto path = dir.path() / ("chlist" + std::to_string(change) + ".exr");
        ExrPicture picture(kWindow, kRgb);
        writeScanline(path, picture, Imf::HALF, Imf::ZIP_COMPRESSION);
        patchAttribute(path, "channels", "chlist", -1, 3 * 18 + 1 + change);  // the size field itself
        expectImageFileRefused(path, "OpenEXR");
    }
}

TEST(ExrImageReader, SideLargerThanTheLimitIsRefusedFromTheHeader) {
    TempDir dir;
    const auto path = dir.path() / "wide.exr";
    ExrPicture picture(kWindow, kRgb);
    writeScanline(path, picture, Imf::HALF, Imf::ZIP_COMPRESSION);
    patchAttribute(path, "dataWindow", "box2i", 2, maxImageSide);
    expectImageFileRefused(path, "image is 16385x5, larger than the limit of 16384 per side");
}

TEST(ExrImageReader, TruncatedFileIsOneError) {
    TempDir dir;
    ExrPicture picture(Imath::Box2i({0, 0}, {40, 90}), kRgb);
    for (const bool tiled : {false, true}) {
        const auto path = dir.path() / (tiled ? "tiled.exr" : "scanline.exr");
        if (tiled)
            writeTiled(path, picture, Imf::FLOAT, Imf::PIZ_COMPRESSION);
        else
            writeScanline(path, picture, Imf::FLOAT, Imf::PIZ_COMPRESSION);
        std::filesystem::resize_file(path, std::filesystem::file_size(path) * 2 / 3);
        expectImageFileRefused(path, "cannot decode OpenEXR image");
    }
}

}  // namespace
}  // namespace raycache
