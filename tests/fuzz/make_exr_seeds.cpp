// Writes the OpenEXR seeds of fuzz_image_loader (tests/fuzz/corpus/image_loader/exr_*)
// with OpenEXR's own writer classes: small smooth pictures, so that every
// block is really compressed (OpenEXR stores a block raw when compressing
// does not make it smaller), in the layouts and compressions the reader takes.
// Each file starts with the byte 5, which picks the .exr extension in the fuzzer. Not part
// of the build; run from the repository root after changing it:
//   g++ -std=c++20 -O1 tests/fuzz/make_exr_seeds.cpp $(pkg-config --cflags --libs OpenEXR) -o /tmp/make_exr_seeds
//   /tmp/make_exr_seeds tests/fuzz/corpus/image_loader
#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfMultiPartOutputFile.h>
#include <ImfOutputFile.h>
#include <ImfOutputPart.h>
#include <ImfPartType.h>
#include <ImfTileDescription.h>
#include <ImfTiledOutputFile.h>
#include <ImfTiledOutputPart.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

// Half planes of a gentle gradient, one per channel, over `window`.
struct Picture {
    Picture(Imath::Box2i window_, std::vector<std::string> channels_)
        : window(window_), channels(std::move(channels_)) {
        const int width = window.max.x - window.min.x + 1, height = window.max.y - window.min.y + 1;
        for (std::size_t c = 0; c < channels.size(); ++c) {
            planes.emplace_back();
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) planes.back().push_back(half(0.25f * (c + 1) + 0.03f * x + 0.05f * y));
        }
    }
    Imf::Header header(Imf::Compression compression) const {
        Imf::Header h(window, window);
        h.compression() = compression;
        for (const std::string& name : channels) h.channels().insert(name, Imf::Channel(Imf::HALF));
        return h;
    }
    Imf::FrameBuffer frameBuffer() {
        Imf::FrameBuffer frame;
        for (std::size_t c = 0; c < channels.size(); ++c)
            frame.insert(channels[c], Imf::Slice::Make(Imf::HALF, planes[c].data(), window));
        return frame;
    }
    int height() const { return window.max.y - window.min.y + 1; }

    Imath::Box2i window;
    std::vector<std::string> channels;
    std::vector<std::vector<half>> planes;
};

const Imath::Box2i k16({0, 0}, {15, 15});
const std::vector<std::string> kRgb = {"R", "G", "B"};

void scanline(const std::string& path, Picture picture, Imf::Compression compression) {
    Imf::OutputFile out(path.c_str(), picture.header(compression));
    out.setFrameBuffer(picture.frameBuffer());
    out.writePixels(picture.height());
}

void tiled(const std::string& path, Picture picture, Imf::Compression compression, Imf::LevelMode levels,
           int tileSize = 8) {
    Imf::Header header = picture.header(compression);
    header.setTileDescription(Imf::TileDescription(tileSize, tileSize, levels));
    Imf::TiledOutputFile out(path.c_str(), header);
    out.setFrameBuffer(picture.frameBuffer());
    for (int level = 0; level < out.numLevels(); ++level)
        out.writeTiles(0, out.numXTiles(level) - 1, 0, out.numYTiles(level) - 1, level);
}

void multipart(const std::string& path) {
    Picture grey(k16, {"Y"});
    Picture colour(Imath::Box2i({-4, 3}, {11, 10}), kRgb);
    Imf::Header headers[2] = {grey.header(Imf::ZIP_COMPRESSION), colour.header(Imf::ZIPS_COMPRESSION)};
    headers[0].setName("grey");
    headers[0].setType(Imf::TILEDIMAGE);
    headers[0].setTileDescription(Imf::TileDescription(8, 8));
    headers[1].setName("colour");
    headers[1].setType(Imf::SCANLINEIMAGE);
    headers[1].displayWindow() = k16;  // shared by every part
    Imf::MultiPartOutputFile out(path.c_str(), headers, 2);
    Imf::TiledOutputPart first(out, 0);
    first.setFrameBuffer(grey.frameBuffer());
    first.writeTiles(0, first.numXTiles() - 1, 0, first.numYTiles() - 1);
    Imf::OutputPart second(out, 1);
    second.setFrameBuffer(colour.frameBuffer());
    second.writePixels(colour.height());
}

// The fuzzer's input: the extension byte, then the file.
void seed(const std::filesystem::path& dir, const std::string& name, void (*write)(const std::string&)) {
    const std::string temp = (dir / (name + ".tmp")).string();
    write(temp);
    std::ifstream in(temp, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(dir / name, std::ios::binary) << '\x05' << bytes;
    std::filesystem::remove(temp);
    std::printf("%s: %zu bytes\n", name.c_str(), bytes.size() + 1);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_exr_seeds <corpus directory>\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    seed(dir, "exr_scanline_piz", [](const std::string& p) { scanline(p, Picture(k16, kRgb), Imf::PIZ_COMPRESSION); });
    seed(dir, "exr_scanline_b44a",
         [](const std::string& p) { scanline(p, Picture(k16, kRgb), Imf::B44A_COMPRESSION); });
    seed(dir, "exr_scanline_dwab_offset", [](const std::string& p) {
        scanline(p, Picture(Imath::Box2i({-7, 20}, {8, 35}), kRgb), Imf::DWAB_COMPRESSION);
    });
    seed(dir, "exr_tiled_piz", [](const std::string& p) {
        // PIZ's tables outweigh what it saves on 8x8 tiles, which are then stored raw.
        tiled(p, Picture(Imath::Box2i({0, 0}, {15, 23}), kRgb), Imf::PIZ_COMPRESSION, Imf::ONE_LEVEL, 16);
    });
    seed(dir, "exr_tiled_mipmap_rle",
         [](const std::string& p) { tiled(p, Picture(k16, kRgb), Imf::RLE_COMPRESSION, Imf::MIPMAP_LEVELS); });
    seed(dir, "exr_tiled_pxr24_grey",
         [](const std::string& p) { tiled(p, Picture(k16, {"Y"}), Imf::PXR24_COMPRESSION, Imf::ONE_LEVEL); });
    seed(dir, "exr_multipart", &multipart);
    return 0;
}
