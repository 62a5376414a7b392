// libFuzzer target: mesh files through our Assimp wrapper (loadMeshFile, with
// its validation). The first byte picks the file extension, since Assimp picks
// its importer by extension first; the rest is the file. Bad input must end in
// InputError; anything else is a finding.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScratchDir.h"
#include "core/Errors.h"
#include "scene/MeshLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    // The formats docs/scene-format.md names, plus two Assimp reads as well.
    // PLY came last, once the loader checked PLY headers itself (Assimp 5.2.5
    // looped forever on some, tests/fuzz/findings/assimp-ply-hang.ply), so the
    // seeds' first bytes, 0-5, still pick what they picked before.
    static constexpr std::array<const char*, 7> kExtensions = {".obj", ".gltf", ".glb", ".off", ".stl", ".dae", ".ply"};
    const std::string name = std::string("mesh") + kExtensions[data[0] % kExtensions.size()];
    const raycache::FuzzScratchDir& dir = raycache::fuzzScratchDir();
    dir.clear();
    const auto path = dir.write(name, data + 1, size - 1);
    try {
        (void)raycache::loadMeshFile(path);
    } catch (const raycache::InputError&) {
        // The documented answer to a bad file.
    }
    return 0;
}
