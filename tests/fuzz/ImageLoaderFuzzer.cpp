// libFuzzer target: texture and environment images through loadImageFile (stb
// for PNG/JPEG/BMP/TGA/HDR, OpenEXR for EXR, with our size and finiteness
// checks). The first byte picks the extension, which picks the decoder; the
// rest is the file. Bad input must end in InputError; anything else is a finding.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScratchDir.h"
#include "core/Errors.h"
#include "scene/ImageLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    // EXR seeds (exr_*) cover scanline and tiled files, multi-part, and most
    // compressions; tests/fuzz/make_exr_seeds.cpp writes them.
    static constexpr std::array<const char*, 6> kExtensions = {".png", ".jpg", ".bmp", ".tga", ".hdr", ".exr"};
    const std::string name = std::string("image") + kExtensions[data[0] % kExtensions.size()];
    const raycache::FuzzScratchDir& dir = raycache::fuzzScratchDir();
    dir.clear();
    const auto path = dir.write(name, data + 1, size - 1);
    try {
        (void)raycache::loadImageFile(path);
    } catch (const raycache::InputError&) {
        // The documented answer to a bad file.
    }
    return 0;
}
