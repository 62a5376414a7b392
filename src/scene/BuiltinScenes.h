#pragma once
// Scenes that need no files, reproducing the set-ups of the source documents.
// Their coordinates are listed in docs/builtin-scenes.md and must stay fixed:
// benchmark figures and reference images depend on them.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/Scene.h"

namespace raycache {

struct BuiltinSceneInfo {
    std::string name;
    std::string description;
};

// Every built-in scene, in a stable order.
std::vector<BuiltinSceneInfo> builtinScenes();

// The named scene, or nothing if no built-in scene has that name.
std::optional<Scene> makeBuiltinScene(std::string_view name);

}  // namespace raycache
