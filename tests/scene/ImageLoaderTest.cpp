#include <gtest/gtest.h>

#include "ImageFileRefusal.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "TempDir.h"
#include "core/ColorSpace.h"
#include "core/Errors.h"
#include "render/ImageWriter.h"
#include "scene/ImageLoader.h"

namespace raycache {
namespace {

const std::filesystem::path imageDir = std::filesystem::path(RAYCACHE_TEST_DATA_DIR) / "images";

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
// channels and the same with 16-bit half channels. Every value is exact in
// half precision, so both must decode to exactly these.
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

// known-half.exr rewritten by OpenEXR's own exrmaketiled (ZIP-compressed 2x2 tiles).
TEST(ImageLoader, TiledExrFromAnotherWriter) {
    expectKnownExrPixels(loadImageFile(imageDir / "known-half-zip-tiled.exr"));
}

// Version flags set by hand on a scanline file (byte 5 holds bits 8-15): each
// announces attributes the header lacks, and OpenEXR says which.
TEST(ImageLoader, ExrVersionFlagsContradictingTheHeaderAreOneError) {
    std::ifstream in(imageDir / "known-half.exr", std::ios::binary);
    const std::string scanline((std::istreambuf_iterator<char>(in)), {});
    TempDir dir;
    const auto withFlag = [&](const std::string& name, char flag) {
        std::string bytes = scanline;
        bytes[5] = static_cast<char>(bytes[5] | flag);
        const auto path = dir.path() / name;
        std::ofstream(path, std::ios::binary) << bytes;
        return path;
    };
    expectImageFileRefused(withFlag("tiled.exr", 0x02), "'tiles' attribute for tiled file not found");
    expectImageFileRefused(withFlag("deep.exr", 0x08), "'type' attribute for v2+ file not found");
    expectImageFileRefused(withFlag("multipart.exr", 0x10), "'name' attribute for multipart file not found");
    EXPECT_EQ(loadImageFile(withFlag("same.exr", 0x00)).width(), 3);
}

// known-half.exr with its G channel's type, HALF (1), set to UINT (0).
TEST(ImageLoader, ExrWithIntegerColourIsRefused) {
    std::ifstream in(imageDir / "known-half.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string halfG("G\0\x01\0\0\0", 6);
    const std::size_t at = bytes.find(halfG);
    ASSERT_NE(at, std::string::npos);
    bytes[at + 2] = '\0';
    TempDir dir;
    const auto path = dir.path() / "uint-g.exr";
    std::ofstream(path, std::ios::binary) << bytes;
    expectImageFileRefused(path, "OpenEXR channel \"G\" holds 32-bit integers");
}

TEST(ImageLoader, ExtensionIsCaseInsensitive) {
    TempDir dir;
    const auto upper = dir.path() / "TINY.PNG";
    std::filesystem::copy_file(imageDir / "tiny.png", upper);
    EXPECT_EQ(loadImageFile(upper).width(), 2);
}

TEST(ImageLoader, MissingFileThrows) {
    expectImageFileRefused(imageDir / "no-such-image.png", "not found");
}

TEST(ImageLoader, UnsupportedExtensionThrows) {
    TempDir dir;
    const auto path = dir.path() / "picture.gif";
    std::ofstream(path) << "GIF89a";
    expectImageFileRefused(path, "unsupported");
}

TEST(ImageLoader, CorruptDataThrows) {
    TempDir dir;
    for (const char* name : {"corrupt.png", "corrupt.jpg", "corrupt.hdr", "corrupt.exr"}) {
        const auto path = dir.path() / name;
        std::ofstream(path) << "this is not an image at all";
        expectImageFileRefused(path);
    }
}

TEST(ImageLoader, TruncatedPngThrows) {
    TempDir dir;
    const auto path = dir.path() / "truncated.png";
    std::filesystem::copy_file(imageDir / "tiny.png", path);
    std::filesystem::resize_file(path, 40);
    expectImageFileRefused(path);
}

TEST(ImageLoader, EightBitDataNamedHdrThrows) {
    TempDir dir;
    const auto path = dir.path() / "really-a-png.hdr";
    std::filesystem::copy_file(imageDir / "tiny.png", path);
    expectImageFileRefused(path, "Radiance");
}

TEST(ImageLoader, AbsurdSizeThrows) {
    TempDir dir;
    const auto path = dir.path() / "wide.png";
    writeImage(Image(maxImageSide + 1, 1), path);
    expectImageFileRefused(path, "larger than the limit");
}

// Found by fuzzing (docs/testing.md): a 33-byte TGA whose header claims
// 16384x10752 pixels made stb allocate and clear half a gigabyte (14 s under
// ASan). Rejected from the header, before any pixel is decoded.
TEST(ImageLoader, HeaderClaimingFarMorePixelsThanTheFileCanHoldThrows) {
    expectImageFileRefused(imageDir / "fuzz-tga-huge-claimed-size.tga", "16384x10752 pixels in a file of 33 bytes");
}

// Found by fuzzing tinyexr (docs/testing.md, findings 1 and 10): a "type"
// attribute contradicting the layout or unknown, a tile of height 0 and an
// attribute name longer than the format allows made tinyexr abort. Each is
// one error naming the file now.
TEST(ImageLoader, ExrHeadersThatAbortedTinyexrAreOneError) {
    expectImageFileRefused(imageDir / "fuzz-tiled-type-in-scanline.exr", "'tiles' attribute for tiled file not found");
    expectImageFileRefused(imageDir / "fuzz-zero-tile-height.exr", "Invalid tile description size (514 x 0)");

    std::ifstream in(imageDir / "known-half-typed.exr", std::ios::binary);
    const std::string typed((std::istreambuf_iterator<char>(in)), {});
    TempDir dir;
    const auto edited = [&](const std::string& name, const std::string& to) {
        const std::string from = "scanlineimage";
        std::string bytes = typed;
        const std::size_t at = bytes.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos) bytes.replace(at, from.size(), to);
        const auto path = dir.path() / name;
        std::ofstream(path, std::ios::binary) << bytes;
        return path;
    };
    expectImageFileRefused(edited("tiled-type.exr", std::string("tiledimage\0\0\0", 13)),
                               "'tiles' attribute for tiled file not found");
    expectImageFileRefused(edited("unknown-type.exr", "scanlineimagX"), "Invalid type string 'scanlineimagX'");
    expectKnownExrPixels(loadImageFile(edited("same.exr", "scanlineimage")));

    // An attribute name of 300 bytes, first in the header.
    std::string bytes = typed;
    bytes.insert(8, std::string(300, 'n') + std::string("\0string\0\0\0\0\0", 12));
    const auto path = dir.path() / "long-name.exr";
    std::ofstream(path, std::ios::binary) << bytes;
    expectImageFileRefused(path, "Invalid attribute name encountered");
}

TEST(ImageLoader, NonFiniteExrPixelThrows) {
    TempDir dir;
    const auto path = dir.path() / "nan.exr";
    Image image(3, 2);
    image.at(2, 1).g = std::numeric_limits<float>::quiet_NaN();
    writeImage(image, path);
    expectImageFileRefused(path, "pixel (2, 1)");
}

}  // namespace
}  // namespace raycache
