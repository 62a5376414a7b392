#pragma once
// A glTF 2.0 file (.gltf, .glb) as a whole scene: its node hierarchy baked
// into world-space mesh objects, its materials shaded by glTF's
// metallic-roughness BRDF (or mapped to Blinn-Phong, scene/PbrToBlinnPhong.h), its first camera and its KHR_lights_punctual
// lights. What raycache cannot show (skins, morph targets, animations,
// emission, ...) is said in one note per feature. docs/scene-format.md,
// "glTF 2.0 scenes", has the rules.
#include <filesystem>

#include "scene/Scene.h"

namespace raycache {

// Whether `path` names a glTF file by its extension (.gltf or .glb, any case).
bool isGltfPath(const std::filesystem::path& path);

// What a JSON scene that includes the file (its "include" key) sets itself.
struct GltfSceneOverrides {
    // The camera: the file's (or the framed one) is still made, for the JSON
    // to change what it names, but a missing camera is not noted.
    bool camera = false;
    // The lights: the file's are not read and no default light is added.
    bool lights = false;
    // The materials under the Blinn-Phong mapping (scene/PbrToBlinnPhong.h,
    // blinnPhongFromPbr) instead of glTF's own BRDF: for comparisons.
    bool blinnPhongMaterials = false;
};

// Reads the glTF 2.0 file at `path` as a scene. Throws InputError, one line
// naming the file (and the node, material, camera or light at fault), for
// a file that is missing or broken, is glTF 1.0, requires an extension
// raycache cannot honour, holds no triangles, or breaks the mesh rules of
// docs/scene-format.md ("Meshes: what is refused, what is repaired").
Scene loadGltfScene(const std::filesystem::path& path, const GltfSceneOverrides& overrides = {});

}  // namespace raycache
