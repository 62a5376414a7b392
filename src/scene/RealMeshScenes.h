#pragma once
// Built-in scenes around real meshes: the Stanford bunny, the Utah teapot and
// the Stanford dragon among mirrors and glass. Unlike scene/BuiltinScenes.h
// they need files, found on a MeshSearchPath (scene/MeshSearchPath.h): the
// bunny and teapot are committed (tests/data/meshes), the dragon is fetched by
// scripts/install-deps.sh. Their coordinates are in docs/builtin-scenes.md.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/MeshSearchPath.h"
#include "scene/Scene.h"

namespace raycache {

struct RealMeshSceneInfo {
    std::string name;
    std::string description;
    std::vector<std::string> meshFiles;  // file names looked up on the search path
};

// Every real-mesh scene, in a stable order.
std::vector<RealMeshSceneInfo> realMeshScenes();

// Empty when every mesh file of `scene` is on `searchPath`; else one line
// saying which file is missing where, and how to get it.
std::string missingMeshFiles(const RealMeshSceneInfo& scene, const MeshSearchPath& searchPath);

// The named scene with its meshes read from `searchPath` (their repair notes
// in Scene::notes), or nothing if no real-mesh scene has that name. Throws
// InputError, one line naming the scene and the file, when a mesh file is
// missing (missingMeshFiles()) or cannot be loaded (scene/MeshLoader.h).
std::optional<Scene> makeRealMeshScene(std::string_view name, const MeshSearchPath& searchPath);

}  // namespace raycache
