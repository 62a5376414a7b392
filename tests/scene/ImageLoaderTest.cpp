#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "core/ColorSpace.h"
#include "core/Errors.h"
#include "render/ImageWriter.h"
#include "scene/ImageLoader.h"

namespace raycache {
namespace {

const std::filesystem::path imageDir = std::filesystem::path(RAYCACHE_TEST_DATA_DIR) / "images";

// A fresh directory under the system temp dir, removed with everything in it.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() /
                ("raycache-" + std::string(info->test_suite_name()) + "-" + info->name());
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

void expectInputErrorNamingFile(const std::filesystem::path& path, const std::string& detail = "") {
    try {
        loadImageFile(path);
        FAIL() << "no exception for " << path;
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(path.string()), std::string::npos) << what;
        EXPECT_NE(what.find(detail), std::string::npos) << what;
        EXPECT_EQ(e.where().file, path.string());
    }
}

TEST(ImageLoader, PngIsDecodedFromSrgbAndAlphaIsDropped) {
    const Image image = loadImageFile(imageDir / "tiny.png");
    ASSERT_EQ(image.width(), 2);
    ASSERT_EQ(image.height(), 2);
    // Row 0 is the top of the picture.
    EXPECT_EQ(image.at(0, 0), Rgb(1, 0, 0));
    EXPECT_EQ(image.at(1, 0), Rgb(0, 1, 0));  // alpha 0 there
    EXPECT_EQ(image.at(0, 1), Rgb(0, 0, 1));
    const float gray = srgbToLinear(128.0f / 255.0f);
    EXPECT_NEAR(gray, 0.2158605f, 1e-6f);
    EXPECT_EQ(image.at(1, 1), Rgb(gray));
}

TEST(ImageLoader, RadianceHdrIsLinear) {
    const Image image = loadImageFile(imageDir / "tiny.hdr");
    ASSERT_EQ(image.width(), 2);
    ASSERT_EQ(image.height(), 2);
    EXPECT_EQ(image.at(0, 0), Rgb(1.0f, 0.5f, 2.0f));
    EXPECT_EQ(image.at(1, 0), Rgb(0.25f, 0.0f, 1.0f));
    EXPECT_EQ(image.at(0, 1), Rgb(4.0f));
    EXPECT_EQ(image.at(1, 1), Rgb(0.0f));
}

// EXR files not written by our own code (tests/data/images/make_known_exr.py
// says how they were made): a hand-made uncompressed file with 32-bit float
// channels, the same with 16-bit half channels, and that half file rewritten
// by OpenEXR's own exrmaketiled as ZIP-compressed 2x2 tiles. Every value is
// exact in half precision, so all three must decode to exactly these.
void expectKnownExrPixels(const Image& image) {
    ASSERT_EQ(image.width(), 3);
    ASSERT_EQ(image.height(), 2);
    EXPECT_EQ(image.at(0, 0), Rgb(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(image.at(1, 0), Rgb(2.0f, 0.0f, 0.125f));
    EXPECT_EQ(image.at(2, 0), Rgb(0.0f));
    EXPECT_EQ(image.at(0, 1), Rgb(4.0f, 8.0f, 16.0f));
    EXPECT_EQ(image.at(1, 1), Rgb(0.75f, 0.375f, 1.5f));
    EXPECT_EQ(image.at(2, 1), Rgb(1024.0f, 0.0625f, 3.0f));
}

TEST(ImageLoader, ExrFromAnotherWriterFloatChannels) {
    expectKnownExrPixels(loadImageFile(imageDir / "known-float.exr"));
}

TEST(ImageLoader, ExrFromAnotherWriterHalfChannels) {
    expectKnownExrPixels(loadImageFile(imageDir / "known-half.exr"));
}

TEST(ImageLoader, ExrWrittenByOpenExrZipTiles) {
    expectKnownExrPixels(loadImageFile(imageDir / "known-half-zip-tiled.exr"));
}

TEST(ImageLoader, ExtensionIsCaseInsensitive) {
    TempDir dir;
    const auto upper = dir.path() / "TINY.PNG";
    std::filesystem::copy_file(imageDir / "tiny.png", upper);
    EXPECT_EQ(loadImageFile(upper).width(), 2);
}

TEST(ImageLoader, MissingFileThrows) {
    expectInputErrorNamingFile(imageDir / "no-such-image.png", "not found");
}

TEST(ImageLoader, UnsupportedExtensionThrows) {
    TempDir dir;
    const auto path = dir.path() / "picture.gif";
    std::ofstream(path) << "GIF89a";
    expectInputErrorNamingFile(path, "unsupported");
}

TEST(ImageLoader, CorruptDataThrows) {
    TempDir dir;
    for (const char* name : {"corrupt.png", "corrupt.jpg", "corrupt.hdr", "corrupt.exr"}) {
        const auto path = dir.path() / name;
        std::ofstream(path) << "this is not an image at all";
        expectInputErrorNamingFile(path);
    }
}

TEST(ImageLoader, TruncatedPngThrows) {
    TempDir dir;
    const auto path = dir.path() / "truncated.png";
    std::filesystem::copy_file(imageDir / "tiny.png", path);
    std::filesystem::resize_file(path, 40);
    expectInputErrorNamingFile(path);
}

TEST(ImageLoader, EightBitDataNamedHdrThrows) {
    TempDir dir;
    const auto path = dir.path() / "really-a-png.hdr";
    std::filesystem::copy_file(imageDir / "tiny.png", path);
    expectInputErrorNamingFile(path, "Radiance");
}

TEST(ImageLoader, AbsurdSizeThrows) {
    TempDir dir;
    const auto path = dir.path() / "wide.png";
    writeImage(Image(maxImageSide + 1, 1), path);
    expectInputErrorNamingFile(path, "larger than the limit");
}

// Found by fuzzing (docs/testing.md): a 33-byte TGA whose header claims
// 16384x10752 pixels made stb allocate and clear half a gigabyte (14 s under
// ASan). Rejected from the header, before any pixel is decoded.
TEST(ImageLoader, HeaderClaimingFarMorePixelsThanTheFileCanHoldThrows) {
    expectInputErrorNamingFile(imageDir / "fuzz-tga-huge-claimed-size.tga", "16384x10752 pixels in a file of 33 bytes");
}

// Found by fuzzing (docs/testing.md): tinyexr asserts, aborting the whole
// program, on a header whose "type" contradicts the file's layout, on an
// unknown type, and on a "tiles" attribute of the wrong size. Each must be an
// InputError naming the file instead. The first file is the fuzzer's input.
TEST(ImageLoader, ExrHeaderThatWouldAbortTinyexrThrows) {
    expectInputErrorNamingFile(imageDir / "fuzz-tiled-type-in-scanline.exr", "type \"tiledimage\"");

    // Byte edits of the OpenEXR-written tiled file.
    std::ifstream in(imageDir / "known-half-zip-tiled.exr", std::ios::binary);
    const std::string tiled((std::istreambuf_iterator<char>(in)), {});
    TempDir dir;
    const auto edited = [&](const std::string& name, const std::string& from, const std::string& to) {
        std::string bytes = tiled;
        const std::size_t at = bytes.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos) bytes.replace(at, from.size(), to);
        const auto path = dir.path() / name;
        std::ofstream(path, std::ios::binary) << bytes;
        return path;
    };
    expectInputErrorNamingFile(edited("unknown-type.exr", "tiledimage", "tiledimagX"), "type \"tiledimagX\"");
    expectInputErrorNamingFile(edited("scanline-type.exr", "tiledimage", "scanlineim"), "type \"scanlineim\"");
    // "tiles" "tiledesc" then the size, 9 as a little-endian int32.
    expectInputErrorNamingFile(
        edited("tiles-size.exr", std::string("tiledesc\0\x09\0\0\0", 13), std::string("tiledesc\0\x08\0\0\0", 13)),
        "tiles attribute has 8 bytes");
    // Tile sides: 2 x 2 in the file, little-endian right after the size 9.
    const std::string tilesAttribute("tiledesc\0\x09\0\0\0\x02\0\0\0\x02\0\0\0", 21);
    expectInputErrorNamingFile(edited("zero-tile.exr", tilesAttribute,
                                      std::string("tiledesc\0\x09\0\0\0\x02\0\0\0\0\0\0\0", 21)),
                               "tiles with a side of 0 pixels");
    expectInputErrorNamingFile(edited("huge-tile.exr", tilesAttribute,
                                      std::string("tiledesc\0\x09\0\0\0\x02\0\0\0\xff\xff\xff\x7f", 21)),
                               "tiles of 2147483647 pixels a side");
    expectInputErrorNamingFile(imageDir / "fuzz-zero-tile-height.exr", "tiles with a side of 0 pixels");
    // The unedited file still loads, so the edits are what is rejected.
    EXPECT_EQ(loadImageFile(edited("same.exr", "tiledimage", "tiledimage")).width(), 3);
}

TEST(ImageLoader, NonFiniteExrPixelThrows) {
    TempDir dir;
    const auto path = dir.path() / "nan.exr";
    Image image(3, 2);
    image.at(2, 1).g = std::numeric_limits<float>::quiet_NaN();
    writeImage(image, path);
    expectInputErrorNamingFile(path, "pixel (2, 1)");
}

}  // namespace
}  // namespace raycache
