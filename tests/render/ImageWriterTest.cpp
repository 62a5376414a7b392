#include "render/ImageWriter.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "TempDir.h"
#include "core/ColorSpace.h"
#include "core/Errors.h"
#include "scene/ImageLoader.h"

namespace raycache {
namespace {

bool isEmptyDir(const std::filesystem::path& dir) {
    return std::filesystem::directory_iterator(dir) == std::filesystem::directory_iterator();
}

// A small image with values across [0, 1] plus out-of-range ones the PNG path must clamp.
Image testImage() {
    Image image(5, 3);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            image.at(x, y) = Rgb(static_cast<float>(x) / 4.0f, static_cast<float>(y) / 2.0f,
                                 static_cast<float>(x * 3 + y) / 17.0f);
    image.at(0, 0) = Rgb(-0.5f, 7.0f, 0.001f);
    return image;
}

TEST(ColorSpace, KnownValues) {
    EXPECT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_EQ(linearToSrgb(1.0f), 1.0f);
    EXPECT_EQ(srgbToLinear(0.0f), 0.0f);
    EXPECT_EQ(srgbToLinear(1.0f), 1.0f);
    EXPECT_NEAR(linearToSrgb(0.5f), 0.7353569830524495f, 1e-7f);
    EXPECT_NEAR(srgbToLinear(0.7353569830524495f), 0.5f, 1e-7f);
    // The linear segment near black.
    EXPECT_NEAR(linearToSrgb(0.001f), 0.01292f, 1e-8f);
    EXPECT_NEAR(srgbToLinear(0.02f), 0.02f / 12.92f, 1e-9f);
}

TEST(ColorSpace, RoundTripsAndIsMonotonic) {
    float previous = -1.0f;
    for (int i = 0; i <= 1000; ++i) {
        const float v = static_cast<float>(i) / 1000.0f;
        EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 1e-6f);
        const float encoded = linearToSrgb(v);
        EXPECT_GT(encoded, previous);
        previous = encoded;
    }
}

TEST(ImageWriter, PngRoundTripWithinOneStep) {
    TempDir dir;
    const auto path = dir.path() / "out.png";
    const Image original = testImage();
    writeImage(original, path);
    const Image back = loadImageFile(path);
    ASSERT_EQ(back.width(), original.width());
    ASSERT_EQ(back.height(), original.height());
    const auto encoded = [](float v) { return linearToSrgb(std::fmin(std::fmax(v, 0.0f), 1.0f)); };
    for (int y = 0; y < original.height(); ++y)
        for (int x = 0; x < original.width(); ++x) {
            const Rgb a = original.at(x, y), b = back.at(x, y);
            EXPECT_NEAR(encoded(b.r), encoded(a.r), 0.5f / 255.0f + 1e-6f) << x << "," << y;
            EXPECT_NEAR(encoded(b.g), encoded(a.g), 0.5f / 255.0f + 1e-6f) << x << "," << y;
            EXPECT_NEAR(encoded(b.b), encoded(a.b), 0.5f / 255.0f + 1e-6f) << x << "," << y;
        }
    // Exactly representable values survive exactly.
    EXPECT_EQ(back.at(0, 0).r, 0.0f);
    EXPECT_EQ(back.at(0, 0).g, 1.0f);
    EXPECT_EQ(back.at(4, 2).r, 1.0f);
}

TEST(ImageWriter, ExrRoundTripIsBitExact) {
    TempDir dir;
    const auto path = dir.path() / "out.exr";
    Image original = testImage();
    original.at(1, 1) = Rgb(1e-30f, 65504.0f * 4.0f, 0.1f);  // beyond half precision
    writeImage(original, path);
    const Image back = loadImageFile(path);
    ASSERT_EQ(back.width(), original.width());
    ASSERT_EQ(back.height(), original.height());
    EXPECT_EQ(std::memcmp(back.pixels().data(), original.pixels().data(),
                          original.pixels().size() * sizeof(Rgb)),
              0);
}

TEST(ImageWriter, LargerExrRoundTripIsBitExact) {
    // Large enough for several ZIP blocks of 16 scanlines.
    TempDir dir;
    const auto path = dir.path() / "big.exr";
    Image original(67, 41);
    for (int y = 0; y < original.height(); ++y)
        for (int x = 0; x < original.width(); ++x)
            original.at(x, y) = Rgb(std::sin(static_cast<float>(x * y)), static_cast<float>(x) * 0.37f,
                                    static_cast<float>(y) / 3.0f);
    writeImage(original, path);
    const Image back = loadImageFile(path);
    ASSERT_EQ(back.width(), original.width());
    ASSERT_EQ(back.height(), original.height());
    EXPECT_EQ(back.pixels(), original.pixels());
}

// What other programs see: float R, G, B over the whole image, ZIP-compressed
// scanlines, read back by OpenEXR itself with the values written.
TEST(ImageWriter, ExrIsFloatRgbZipScanlines) {
    TempDir dir;
    const auto path = dir.path() / "out.exr";
    const Image original = testImage();
    writeImage(original, path);
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    EXPECT_EQ(header.compression(), Imf::ZIP_COMPRESSION);
    EXPECT_FALSE(header.hasTileDescription());
    EXPECT_EQ(header.dataWindow(), Imath::Box2i({0, 0}, {original.width() - 1, original.height() - 1}));
    EXPECT_EQ(header.displayWindow(), header.dataWindow());
    std::vector<std::string> names;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
        names.emplace_back(c.name());
        EXPECT_EQ(c.channel().type, Imf::FLOAT) << c.name();
    }
    EXPECT_EQ(names, (std::vector<std::string>{"B", "G", "R"}));
    Image back(original.width(), original.height());
    char* base = reinterpret_cast<char*>(back.pixels().data());
    const std::size_t row = sizeof(Rgb) * static_cast<std::size_t>(back.width());
    Imf::FrameBuffer frame;
    frame.insert("R", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, r), sizeof(Rgb), row));
    frame.insert("G", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, g), sizeof(Rgb), row));
    frame.insert("B", Imf::Slice(Imf::FLOAT, base + offsetof(Rgb, b), sizeof(Rgb), row));
    file.setFrameBuffer(frame);
    file.readPixels(0, back.height() - 1);
    EXPECT_EQ(back.pixels(), original.pixels());
}

TEST(ImageWriter, OverwritesAndLeavesNoTempFile) {
    TempDir dir;
    const auto path = dir.path() / "out.png";
    writeImage(Image(1, 1), path);
    Image white(2, 1);
    white.at(0, 0) = white.at(1, 0) = Rgb(1.0f);
    writeImage(white, path);
    EXPECT_EQ(loadImageFile(path).at(1, 0), Rgb(1.0f));
    int files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 1);
}

TEST(ImageWriter, UnsupportedExtensionThrowsAndWritesNothing) {
    TempDir dir;
    for (const char* name : {"out.jpg", "out.hdr", "out", "out.png.txt"}) {
        const auto path = dir.path() / name;
        EXPECT_FALSE(isSupportedImageExtension(path)) << name;
        EXPECT_THROW(checkWritableImagePath(path), InputError) << name;
        try {
            writeImage(testImage(), path);
            ADD_FAILURE() << "no exception for " << name;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        }
    }
    EXPECT_TRUE(isEmptyDir(dir.path()));
}

TEST(ImageWriter, SupportedExtensions) {
    EXPECT_TRUE(isSupportedImageExtension("a.png"));
    EXPECT_TRUE(isSupportedImageExtension("dir/a.EXR"));
    EXPECT_TRUE(isSupportedImageExtension("A.Png"));
    EXPECT_NO_THROW(checkWritableImagePath("relative.png"));
}

TEST(ImageWriter, MissingDirectoryThrowsAndWritesNothing) {
    TempDir dir;
    const auto path = dir.path() / "missing" / "out.exr";
    EXPECT_THROW(checkWritableImagePath(path), InputError);
    try {
        writeImage(testImage(), path);
        FAIL() << "no exception";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "missing"));
    EXPECT_TRUE(isEmptyDir(dir.path()));
}

TEST(ImageWriter, FailedWriteThrowsRuntimeErrorAndCleansUp) {
    // The target is a directory, so the final rename fails after the data was written.
    TempDir dir;
    const auto path = dir.path() / "taken.png";
    std::filesystem::create_directory(path);
    std::filesystem::create_directory(path / "child");  // a non-empty directory cannot be replaced
    try {
        writeImage(testImage(), path);
        FAIL() << "no exception";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
    int entries = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++entries;
    EXPECT_EQ(entries, 1);  // only the directory itself, no temporary file
}

}  // namespace
// Exposure and view transform change the PNG's codes only: the defaults
// write today's bytes, +1 EV writes the codes of the doubled film, and an
// EXR keeps the film's own values whatever the display settings.
TEST(ImageWriter, DisplaySettingsShapePngsOnly) {
    TempDir dir;
    const Image original = testImage();
    const auto bytes = [](const std::filesystem::path& p) {
        std::ifstream in(p, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    writeImage(original, dir.path() / "plain.png");
    writeImage(original, dir.path() / "defaults.png", DisplaySettings{0.0f, ViewTransform::Standard});
    EXPECT_EQ(bytes(dir.path() / "plain.png"), bytes(dir.path() / "defaults.png"));

    Image doubled = original;
    for (Rgb& p : doubled.pixels()) p *= 2.0f;
    writeImage(original, dir.path() / "plus1.png", DisplaySettings{1.0f, ViewTransform::Standard});
    writeImage(doubled, dir.path() / "doubled.png");
    EXPECT_EQ(bytes(dir.path() / "plus1.png"), bytes(dir.path() / "doubled.png"));

    writeImage(original, dir.path() / "agx.png", DisplaySettings{2.0f, ViewTransform::Agx});
    EXPECT_NE(bytes(dir.path() / "agx.png"), bytes(dir.path() / "plain.png"));
    writeImage(original, dir.path() / "plain.exr");
    writeImage(original, dir.path() / "agx.exr", DisplaySettings{2.0f, ViewTransform::Agx});
    EXPECT_EQ(bytes(dir.path() / "plain.exr"), bytes(dir.path() / "agx.exr"));
}

}  // namespace raycache
