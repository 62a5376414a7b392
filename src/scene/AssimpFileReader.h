#pragma once
// One model file read through Assimp under the project's refusal rules
// (docs/scene-format.md, "Meshes: what is refused, what is repaired"): the
// checks that must run before Assimp sees the file (size, the strict text
// checks, GLB chunk lengths, a glTF file's JSON and its limits, a reader
// that claims the extension), Assimp's
// own validation, faces without vertices and non-finite vertices before any
// post-processing, and, after it, every repair Assimp only admits in its log.
// Shared by the mesh loader (one merged mesh) and the glTF scene loader (a
// whole scene), so that both refuse the same files with the same words.
#include <assimp/Importer.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scene/AssimpLogCapture.h"

struct aiScene;

namespace raycache {

class AssimpFileReader {
public:
    // Whether a glTF file's JSON was checked already (readGltfDocument, by
    // the scene loader), or is checked here (checkGltfBeforeAssimp).
    enum class GltfJson { CheckHere, AlreadyChecked };

    // Reads and validates `path`, not yet post-processed. Throws InputError
    // naming the file for everything listed above. Holds Assimp's one
    // process-wide log (AssimpLogCapture) for its lifetime.
    explicit AssimpFileReader(const std::filesystem::path& path, GltfJson gltfJson = GltfJson::CheckHere);
    AssimpFileReader(const AssimpFileReader&) = delete;
    AssimpFileReader& operator=(const AssimpFileReader&) = delete;

    // The scene as read, before post-processing.
    const aiScene& scene() const { return *scene_; }

    // Applies Assimp's post-processing `steps` and returns the result.
    // Throws InputError if Assimp fails, marks the scene incomplete, or
    // logged a repair of the geometry ("broken mesh, Assimp says: ...").
    const aiScene& postProcess(unsigned steps);

    // What was accepted though odd, for the file's note, in the order met
    // (a PLY header line without a keyword; OBJ material files not found).
    const std::vector<std::string>& acceptedPhrases() const { return phrases_; }

private:
    std::filesystem::path path_;
    std::vector<std::string> phrases_;
    Assimp::Importer importer_;
    std::optional<AssimpLogCapture> log_;  // from the first look Assimp takes at the content
    const aiScene* scene_ = nullptr;
};

}  // namespace raycache
