// libFuzzer target: a JSON scene file through loadSceneFile (parsing, validation,
// building the scene). Bad input must end in InputError; anything else that
// escapes (another exception, a crash, a sanitizer report) is a finding.
#include <cstddef>
#include <cstdint>

#include "FuzzScratchDir.h"
#include "core/Errors.h"
#include "scene/SceneFile.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    const raycache::FuzzScratchDir& dir = raycache::fuzzScratchDir();
    const auto path = dir.write("scene.json", data, size);
    try {
        (void)raycache::loadSceneFile(path);
    } catch (const raycache::InputError&) {
        // The documented answer to a bad file.
    }
    return 0;
}
