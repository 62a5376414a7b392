#pragma once
#include <string>

#include "scene/Scene.h"

namespace raycache {

// A built-in scene by name (scene/BuiltinScenes.h, then scene/RealMeshScenes.h
// with its meshes on meshSearchPathFromEnvironment()), or a scene file by path: glTF 2.0 (.gltf, .glb,
// any case: scene/GltfScene.h), else our JSON (scene/SceneFile.h). Throws
// InputError naming the argument when it is neither.
Scene loadScene(const std::string& builtinNameOrPath);

}  // namespace raycache
