#include <gtest/gtest.h>

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
// Inputs the fuzzers found (docs/testing.md), kept beside the fuzzers.
const std::filesystem::path findingsDir =
    std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings";

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

// Only flat single-part scanline EXR is read: tiled, deep and multi-part files
// are refused from the version field, before tinyexr decodes anything. The
// tiled file is known-half.exr rewritten by OpenEXR's own exrmaketiled
// (ZIP-compressed 2x2 tiles); deep and multi-part are its flags set by hand.
TEST(ImageLoader, TiledDeepAndMultipartExrAreRefused) {
    expectInputErrorNamingFile(imageDir / "known-half-zip-tiled.exr",
                               "tiled EXR is not supported, save it as scanline");
    std::ifstream in(imageDir / "known-half.exr", std::ios::binary);
    const std::string scanline((std::istreambuf_iterator<char>(in)), {});
    TempDir dir;
    const auto withFlag = [&](const std::string& name, char flag) {  // byte 5 holds version bits 8-15
        std::string bytes = scanline;
        bytes[5] = static_cast<char>(bytes[5] | flag);
        const auto path = dir.path() / name;
        std::ofstream(path, std::ios::binary) << bytes;
        return path;
    };
    expectInputErrorNamingFile(withFlag("tiled.exr", 0x02), "tiled EXR is not supported, save it as scanline");
    expectInputErrorNamingFile(withFlag("deep.exr", 0x08), "deep EXR is not supported");
    expectInputErrorNamingFile(withFlag("multipart.exr", 0x10), "multi-part EXR is not supported");
    EXPECT_EQ(loadImageFile(withFlag("same.exr", 0x00)).width(), 3);
}

// Found by fuzzing (docs/testing.md, finding 3): Debian's tinyexr 1.0.1
// crashes (SEGV in LoadEXRWithLayer) on this corrupt ZIP-tiled file. It is
// refused as tiled before tinyexr decodes it: one InputError, no crash.
TEST(ImageLoader, CorruptZipTiledExrFromTheFuzzerIsRefusedNotACrash) {
    const auto finding = findingsDir / "tinyexr-segv-zip-tiled.exr";
    ASSERT_TRUE(std::filesystem::exists(finding)) << finding;
    expectInputErrorNamingFile(finding, "tiled EXR is not supported, save it as scanline");
}

// Found by fuzzing (docs/testing.md, finding 8): an uncompressed scanline
// file whose G channel became 32-bit unsigned integers with too little data;
// tinyexr 1.0.1 read past the end of its buffer (ASan: heap-buffer-overflow in
// DecodePixelData). Integer channels are refused before tinyexr decodes.
TEST(ImageLoader, ExrWithAnIntegerChannelIsRefusedBeforeDecoding) {
    const auto finding = findingsDir / "tinyexr-overread-uint-channel.exr";
    ASSERT_TRUE(std::filesystem::exists(finding)) << finding;
    expectInputErrorNamingFile(finding, "holds 32-bit integers, which are not supported");
    // The same in a well-formed file: known-half.exr with its G channel's type, HALF (1), set to UINT (0).
    std::ifstream in(imageDir / "known-half.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string halfG("G\0\x01\0\0\0", 6);
    const std::size_t at = bytes.find(halfG);
    ASSERT_NE(at, std::string::npos);
    bytes[at + 2] = '\0';
    TempDir dir;
    const auto path = dir.path() / "uint-g.exr";
    std::ofstream(path, std::ios::binary) << bytes;
    expectInputErrorNamingFile(path, "OpenEXR channel \"G\" holds 32-bit integers");
}

// Found by fuzzing (docs/testing.md, finding 9): a file whose compression
// attribute became PIZ; tinyexr 1.0.1's PIZ decoder copied past the end of its
// buffer (ASan: heap-buffer-overflow in DecompressPiz). PIZ is refused.
TEST(ImageLoader, PizCompressedExrIsRefusedBeforeDecoding) {
    const auto finding = findingsDir / "tinyexr-overread-piz.exr";
    ASSERT_TRUE(std::filesystem::exists(finding)) << finding;
    expectInputErrorNamingFile(finding, "PIZ-compressed EXR is not supported, save it with ZIP compression");
    // known-half.exr with its compression, NONE (0), set to PIZ (4).
    std::ifstream in(imageDir / "known-half.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string none("compression\0compression\0\x01\0\0\0\0", 29);
    const std::size_t at = bytes.find(none);
    ASSERT_NE(at, std::string::npos);
    bytes[at + 28] = '\x04';
    TempDir dir;
    const auto path = dir.path() / "piz.exr";
    std::ofstream(path, std::ios::binary) << bytes;
    expectInputErrorNamingFile(path, "PIZ-compressed EXR is not supported");
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

// Found by fuzzing (docs/testing.md, finding 1): tinyexr asserts, aborting
// the whole program, on a header whose "type" contradicts the file's layout
// and on an unknown type. Each must be an InputError naming the file instead.
// The fuzzer's inputs were tiled files (a tiled version flag without tiles, a
// tile of height 0), now refused as tiled; the type is checked on byte edits
// of a scanline file that has one (make_known_exr.py).
TEST(ImageLoader, ExrHeaderThatWouldAbortTinyexrThrows) {
    expectInputErrorNamingFile(imageDir / "fuzz-tiled-type-in-scanline.exr", "tiled EXR is not supported");
    expectInputErrorNamingFile(imageDir / "fuzz-zero-tile-height.exr", "tiled EXR is not supported");

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
    expectInputErrorNamingFile(edited("tiled-type.exr", std::string("tiledimage\0\0\0", 13)), "type \"tiledimage\"");
    expectInputErrorNamingFile(edited("unknown-type.exr", "scanlineimagX"), "type \"scanlineimagX\"");
    // The unedited file loads, so the edits are what is rejected.
    expectKnownExrPixels(loadImageFile(edited("same.exr", "scanlineimage")));
}

// Found by fuzzing (CI run of stop 22): an unknown "type" behind an attribute
// whose name is longer than 255 bytes. tinyexr reads names of any length, so
// the check must too, or the type slips past it and tinyexr aborts.
TEST(ImageLoader, ExrTypeBehindALongAttributeNameThrows) {
    std::ifstream in(imageDir / "known-half-typed.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::size_t typeAt = bytes.find("scanlineimage");
    ASSERT_NE(typeAt, std::string::npos);
    bytes.replace(typeAt, 13, "scanlineimagX");
    // An empty string attribute with a 300-byte name, first in the header.
    const std::string longNamed = std::string(300, 'n') + std::string("\0string\0\0\0\0\0", 12);
    bytes.insert(8, longNamed);
    TempDir dir;
    const auto path = dir.path() / "long-name.exr";
    std::ofstream(path, std::ios::binary) << bytes;
    expectInputErrorNamingFile(path, "type \"scanlineimagX\"");
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
