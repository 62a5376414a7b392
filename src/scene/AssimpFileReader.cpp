#include "scene/AssimpFileReader.h"

#include <assimp/BaseImporter.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <set>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include "core/Errors.h"
#include "scene/GltfDocument.h"
#include "scene/MeshLimits.h"
#include "scene/MeshTextCheck.h"

namespace raycache {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
    throw InputError(InputLocation{.file = path.string()}, message);
}

// In one read of the file's size: a stream copy grows its buffer by
// doubling, which cost a scanned mesh's 33 MB several copies.
std::string readText(const std::filesystem::path& path, std::uintmax_t bytes) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open mesh file");
    std::string text(static_cast<std::size_t>(bytes), '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    if (in.bad() || in.gcount() != static_cast<std::streamsize>(text.size())) fail(path, "cannot read mesh file");
    return text;
}

// For a binary glTF (a file starting with "glTF", whatever its name): the
// first chunk, of the 12-byte header's file, that claims more bytes than
// follow it; empty if none does. Assimp 5.2 allocates what the JSON chunk
// claims before reading it (4 GiB for a mutated 800-byte file, found by
// fuzzing, docs/testing.md finding 15).
std::string glbChunkBeyondTheEnd(const std::filesystem::path& path, std::uintmax_t fileBytes) {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    if (!in.read(magic, sizeof magic) || std::string(magic, 4) != "glTF") return {};
    std::uint32_t version = 0;  // little-endian, as the machines we build on
    if (!in.read(reinterpret_cast<char*>(&version), sizeof version)) return {};
    if (version == 1) {
        // glTF 1.0's binary layout: a 20-byte header whose fourth word is the
        // JSON content's length, then the content and the binary body.
        std::uint32_t contentLength = 0;
        in.seekg(12);
        if (!in.read(reinterpret_cast<char*>(&contentLength), sizeof contentLength)) return {};
        if (fileBytes < 20 || contentLength > fileBytes - 20)
            return "binary glTF 1.0 content claims " + std::to_string(contentLength) + " bytes, more than the " +
                   std::to_string(fileBytes < 20 ? 0 : fileBytes - 20) + " left in the file";
        return {};
    }
    for (std::uintmax_t at = 12; at + 8 <= fileBytes;) {
        std::uint32_t length = 0;
        in.seekg(static_cast<std::streamoff>(at));
        if (!in.read(reinterpret_cast<char*>(&length), sizeof length)) return {};
        if (length > fileBytes - at - 8)
            return "GLB chunk at byte " + std::to_string(at) + " claims " + std::to_string(length) +
                   " bytes, more than the " + std::to_string(fileBytes - at - 8) + " left in the file";
        at += 8 + length;
    }
    return {};
}

// Assimp's choice of reader, as Importer::ReadFile makes it: the one reader
// that claims the file's extension, or the first of several whose look at
// the content accepts it. Without one, ReadFile would guess the format from
// the content alone, past the checks above that go by the extension (a
// mutated file named .gltf went to the OBJ reader, which freed memory twice;
// a damaged PLY header to the PLY reader, which looped forever:
// docs/testing.md findings 14, 16). Empty if a reader is found, else why not.
std::string noReaderForTheExtension(const Assimp::Importer& importer, const std::filesystem::path& path) {
    std::string name = path.filename().string();
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    std::vector<Assimp::BaseImporter*> claimants;
    for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) {
        std::set<std::string> extensions;
        importer.GetImporter(i)->GetExtensionList(extensions);
        for (const std::string& extension : extensions)
            if (name.size() > extension.size() + 1 && name.ends_with("." + extension)) {
                claimants.push_back(importer.GetImporter(i));
                break;
            }
    }
    if (claimants.empty()) return "no reader in Assimp takes the extension '" + path.extension().string() + "'";
    if (claimants.size() == 1) return {};
    for (Assimp::BaseImporter* reader : claimants)
        if (reader->CanRead(path.string(), importer.GetIOHandler(), true)) return {};
    return "not a " + path.extension().string() + " file: Assimp's readers for it refuse its content";
}

// Whether Assimp's glTF readers take the file by its name (.gltf, .glb).
bool namedGltf(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return extension == ".gltf" || extension == ".glb";
}

std::span<const aiMesh* const> assimpMeshesOf(const aiScene& scene) {
    if (!scene.mMeshes) return {};
    return {scene.mMeshes, scene.mNumMeshes};
}

// "face F of mesh M has no vertices" for the first such face, else empty.
std::string faceWithoutVertices(const aiScene& scene) {
    const auto meshes = assimpMeshesOf(scene);
    for (std::size_t m = 0; m < meshes.size(); ++m)
        for (unsigned f = 0; meshes[m]->mFaces && f < meshes[m]->mNumFaces; ++f)
            if (meshes[m]->mFaces[f].mNumIndices == 0)
                return "face " + std::to_string(f) + " of mesh " + std::to_string(m) + " has no vertices";
    return {};
}

// "N of the file's M vertices are not finite (infinite or NaN)", or empty.
// Checked before post-processing: Assimp's joining of vertices sorts them
// by position, which NaN breaks.
std::string nonFiniteVertices(const aiScene& scene) {
    std::size_t bad = 0, all = 0;
    for (const aiMesh* m : assimpMeshesOf(scene)) {
        all += m->mNumVertices;
        for (unsigned i = 0; m->mVertices && i < m->mNumVertices; ++i) {
            const aiVector3D& p = m->mVertices[i];
            bad += (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) ? 0 : 1;
        }
    }
    if (bad == 0) return {};
    return std::to_string(bad) + " of the file's " + std::to_string(all) + " vertices are not finite (infinite or NaN)";
}

}  // namespace

AssimpFileReader::AssimpFileReader(const std::filesystem::path& path, GltfJson gltfJson) : path_(path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(path, "mesh file not found");
    if (!std::filesystem::is_regular_file(path, ec)) fail(path, "not a regular file");
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (!ec && bytes > kMaxMeshFileBytes)
        fail(path, "mesh file is " + std::to_string(bytes) + " bytes, more than the limit of " +
                       std::to_string(kMaxMeshFileBytes));
    // Text formats Assimp reads leniently are checked strictly first.
    if (strictlyCheckedText(path)) {
        std::string accepted;
        if (const auto problem = checkMeshText(path, readText(path, ec ? 0 : bytes), &accepted))
            throw InputError(InputLocation{.file = path.string(), .line = problem->line, .column = problem->column},
                             problem->message);
        if (!accepted.empty()) phrases_.push_back(accepted);
    }
    if (const std::string chunk = ec ? std::string() : glbChunkBeyondTheEnd(path, bytes); !chunk.empty())
        fail(path, chunk);
    // Before any glTF reader looks at it: their look parses the JSON
    // recursively, and reading it follows the node graph recursively.
    if (gltfJson == GltfJson::CheckHere && namedGltf(path)) checkGltfBeforeAssimp(path);

    if (const std::string why = noReaderForTheExtension(importer_, path); !why.empty()) fail(path, why);
    // Assimp's default logger is silent: listen from here on.
    log_.emplace();
    // The file is read and validated first, and post-processed only once its
    // faces are looked at: Assimp 5.2's triangulation asserts (aborting the
    // process) on a face without vertices, which its PLY reader makes of a
    // corrupt binary body (found by fuzzing, docs/testing.md finding 11).
    scene_ = importer_.ReadFile(path.string(), aiProcess_ValidateDataStructure);
    if (!scene_) fail(path, std::string("Assimp cannot read it: ") + importer_.GetErrorString());
    if (const std::string problem = faceWithoutVertices(*scene_); !problem.empty()) fail(path, problem);
    if (const std::string problem = nonFiniteVertices(*scene_); !problem.empty()) fail(path, problem);
}

const aiScene& AssimpFileReader::postProcess(unsigned steps) {
    scene_ = importer_.ApplyPostProcessing(steps);
    if (!scene_) fail(path_, std::string("Assimp cannot read it: ") + importer_.GetErrorString());
    // Assimp marks a file incomplete when it holds no meshes (only nodes, materials or animations).
    if (scene_->mFlags & AI_SCENE_FLAGS_INCOMPLETE)
        fail(path_, "the file holds no meshes (Assimp marks it incomplete)");
    // A file Assimp had to repair (dropping faces, ignoring normals) is refused:
    // rendering what is left would hide the damage.
    if (!log_->problems().empty()) {
        std::string all = log_->problems().front();
        if (log_->problems().size() > 1) all += " (and " + std::to_string(log_->problems().size() - 1) + " more)";
        fail(path_, "broken mesh, Assimp says: " + all);
    }
    const std::vector<std::string>& missing = log_->missingMaterialFiles();
    if (!missing.empty()) {
        std::string names;
        for (std::size_t i = 0; i < missing.size(); ++i) names += (i ? ", " : "") + missing[i];
        phrases_.push_back(std::string(missing.size() == 1 ? "material file " : "material files ") + names +
                           " not found; the object's material is used");
    }
    return *scene_;
}

}  // namespace raycache
