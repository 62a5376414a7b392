// libFuzzer target: a glTF 2.0 file as a whole scene through loadGltfScene
// (our JSON pre-reading and its limits, Assimp's glTF readers, the scene
// builder: materials, textures, cameras, lights). The first byte picks the
// name's extension, .gltf or .glb (Assimp picks its reader by the extension,
// our pre-reading by the content); the rest is the file. Bad input must end
// in InputError; anything else (another exception, a crash, a sanitizer
// report, a hang) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScratchDir.h"
#include "core/Errors.h"
#include "scene/GltfScene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const std::string name = (data[0] & 1) ? "scene.glb" : "scene.gltf";
    const raycache::FuzzScratchDir& dir = raycache::fuzzScratchDir();
    dir.clear();
    const auto path = dir.write(name, data + 1, size - 1);
    try {
        (void)raycache::loadGltfScene(path);
    } catch (const raycache::InputError&) {
        // The documented answer to a bad file.
    }
    return 0;
}
