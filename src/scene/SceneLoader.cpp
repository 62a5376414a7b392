#include "scene/SceneLoader.h"

#include <filesystem>

#include "core/Errors.h"
#include "scene/BuiltinScenes.h"
#include "scene/SceneFile.h"

namespace raycache {

Scene loadScene(const std::string& builtinNameOrPath) {
    if (auto builtin = makeBuiltinScene(builtinNameOrPath)) return std::move(*builtin);
    const std::filesystem::path path(builtinNameOrPath);
    if (path.extension() == ".json" || std::filesystem::exists(path)) return loadSceneFile(path);
    throw InputError("unknown scene '" + builtinNameOrPath +
                     "': not a built-in scene (see `raycache scenes`) and not a .json file");
}

}  // namespace raycache
