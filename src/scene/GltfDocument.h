#pragma once
// What a glTF file's own JSON says that Assimp does not pass on: the
// version, the extensions the file uses and requires, how many scenes it
// holds. The scene loader refuses a file on these before Assimp reads it
// (glTF 1.0, a required extension raycache cannot honour) and notes the
// extensions it ignores (docs/scene-format.md, "glTF 2.0 scenes").
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/Rgb.h"

namespace raycache {

// A material's KHR_materials_emissive_strength and KHR_materials_specular,
// glTF's defaults where the extension is absent.
struct GltfMaterialExtensions {
    float emissiveStrength = 1.0f;  // multiplies emissiveFactor
    float specularFactor = 1.0f;    // in [0, 1]
    Rgb specularColor{1.0f};        // specularColorFactor, each >= 0
    bool specularTextures = false;  // specularTexture or specularColorTexture, not read
};

struct GltfDocument {
    std::string version;                      // asset.version as written ("2.0"); "1.0" also for a binary glTF 1.0 file
    std::vector<std::string> extensionsUsed;  // in file order
    std::vector<std::string> extensionsRequired;  // in file order
    std::size_t sceneCount = 0;                   // entries of "scenes"
    // Per entry of "cameras" (Assimp keeps their order): whether it is
    // orthographic. Assimp 5.2 gives such a camera a field of view of 0,
    // which a broken perspective camera can have too.
    std::vector<bool> orthographicCameras;
    std::size_t defaultScene = 0;  // "scene", the one drawn
    // Some texture's KHR_texture_transform names its own texture coordinate
    // set ("texCoord"), which Assimp 5.2 does not read.
    bool textureTransformSetsTexCoord = false;
    // Per entry of "materials", what its extensions say that Assimp 5.2
    // does not read. Assimp keeps the file's order of materials, so entry i
    // is Assimp's material i.
    std::vector<GltfMaterialExtensions> materialExtensions;

    bool isVersion2() const { return version.rfind("2.", 0) == 0; }
};

// Reads the JSON of a .gltf file, or the JSON chunk of a binary glTF (a
// file starting with "glTF", whatever its name). Throws InputError naming
// the file if it cannot be read, is larger than a mesh file may be, is not
// JSON (with the line and column of a .gltf file's syntax error), or its
// binary header or chunks do not fit in the file.
// It also checks the limits of GltfLimits.h (node graph, counts, sizes).
GltfDocument readGltfDocument(const std::filesystem::path& path);

// For a file Assimp is about to read as glTF (by its name), when it is not
// read as a scene: what keeps Assimp's glTF readers from running out of
// stack or memory, the JSON's nesting and the limits of GltfLimits.h.
// Content that is not a JSON object is left to Assimp's readers, which
// refuse it. Throws InputError naming the file.
void checkGltfBeforeAssimp(const std::filesystem::path& path);

}  // namespace raycache
