#pragma once
#include <string>

#include "scene/Scene.h"

namespace raycache {

// A built-in scene by name (scene/BuiltinScenes.h, then scene/RealMeshScenes.h
// with its meshes on meshSearchPathFromEnvironment()), or a scene file by path: glTF 2.0 (.gltf, .glb,
// any case: scene/GltfScene.h), else our JSON (scene/SceneFile.h). Throws
// InputError naming the argument when it is neither.
// `blinnPhongGltfMaterials`: a glTF scene's materials under the Blinn-Phong
// mapping (GltfSceneOverrides::blinnPhongMaterials) instead of glTF's BRDF.
Scene loadScene(const std::string& builtinNameOrPath, bool blinnPhongGltfMaterials = false);

}  // namespace raycache
