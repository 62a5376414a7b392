#include "scene/SceneLoader.h"

#include <filesystem>

#include "core/Errors.h"
#include "scene/BuiltinScenes.h"
#include "scene/GltfScene.h"
#include "scene/RealMeshScenes.h"
#include "scene/SceneFile.h"

namespace raycache {

Scene loadScene(const std::string& builtinNameOrPath, bool blinnPhongGltfMaterials) {
    if (auto builtin = makeBuiltinScene(builtinNameOrPath)) return std::move(*builtin);
    if (auto real = makeRealMeshScene(builtinNameOrPath, meshSearchPathFromEnvironment())) return std::move(*real);
    const std::filesystem::path path(builtinNameOrPath);
    // The extension decides: a glTF 2.0 file is a whole scene, anything else our JSON.
    if (isGltfPath(path)) return loadGltfScene(path, GltfSceneOverrides{.blinnPhongMaterials = blinnPhongGltfMaterials});
    if (path.extension() == ".json" || std::filesystem::exists(path)) return loadSceneFile(path);
    throw InputError("unknown scene '" + builtinNameOrPath +
                     "': not a built-in scene (see `raycache scenes`) and not a .json, .gltf or .glb file");
}

}  // namespace raycache
