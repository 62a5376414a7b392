#include "scene/MeshLoader.h"

#include <assimp/BaseImporter.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <limits>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "core/Errors.h"
#include "scene/AssimpLogCapture.h"
#include "scene/MeshLimits.h"
#include "scene/MeshTextCheck.h"

namespace raycache {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
    throw InputError(InputLocation{.file = path.string()}, message);
}

std::string readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open mesh file");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) fail(path, "cannot read mesh file");
    return std::move(text).str();
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
    for (std::uintmax_t at = 12; at + 8 <= fileBytes;) {
        std::uint32_t length = 0;  // little-endian, as the machines we build on
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
    if (claimants.empty())
        return "no reader in Assimp takes the extension '" + path.extension().string() + "'";
    if (claimants.size() == 1) return {};
    for (Assimp::BaseImporter* reader : claimants)
        if (reader->CanRead(path.string(), importer.GetIOHandler(), true)) return {};
    return "not a " + path.extension().string() + " file: Assimp's readers for it refuse its content";
}

std::span<const aiMesh* const> meshesOf(const aiScene& scene) {
    if (!scene.mMeshes) return {};
    return {scene.mMeshes, scene.mNumMeshes};
}

// "face F of mesh M has no vertices" for the first such face, else empty.
std::string faceWithoutVertices(const aiScene& scene) {
    const auto meshes = meshesOf(scene);
    for (std::size_t m = 0; m < meshes.size(); ++m)
        for (unsigned f = 0; meshes[m]->mFaces && f < meshes[m]->mNumFaces; ++f)
            if (meshes[m]->mFaces[f].mNumIndices == 0)
                return "face " + std::to_string(f) + " of mesh " + std::to_string(m) + " has no vertices";
    return {};
}

}  // namespace

TriangleMesh loadMeshFile(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(path, "mesh file not found");
    if (!std::filesystem::is_regular_file(path, ec)) fail(path, "not a regular file");
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (!ec && bytes > kMaxMeshFileBytes)
        fail(path, "mesh file is " + std::to_string(bytes) + " bytes, more than the limit of " +
                       std::to_string(kMaxMeshFileBytes));
    // Text formats Assimp reads leniently are checked strictly first.
    if (strictlyCheckedText(path)) {
        if (const auto problem = checkMeshText(path, readText(path)))
            throw InputError(InputLocation{.file = path.string(), .line = problem->line, .column = problem->column},
                             problem->message);
    }
    if (const std::string chunk = ec ? std::string() : glbChunkBeyondTheEnd(path, bytes); !chunk.empty())
        fail(path, chunk);

    // PreTransformVertices bakes the node hierarchy into the vertices, so the
    // meshes can simply be concatenated. Assimp's default logger is silent.
    Assimp::Importer importer;
    if (const std::string why = noReaderForTheExtension(importer, path); !why.empty()) fail(path, why);
    const AssimpLogCapture log;
    // The file is read and validated first, and post-processed only once its
    // faces are looked at: Assimp 5.2's triangulation asserts (aborting the
    // process) on a face without vertices, which its PLY reader makes of a
    // corrupt binary body (found by fuzzing, docs/testing.md finding 11).
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
    if (!scene) fail(path, std::string("Assimp cannot read it: ") + importer.GetErrorString());
    if (const std::string problem = faceWithoutVertices(*scene); !problem.empty()) fail(path, problem);
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                         aiProcess_GenSmoothNormals | aiProcess_PreTransformVertices |
                                         aiProcess_FindInvalidData);
    if (!scene) fail(path, std::string("Assimp cannot read it: ") + importer.GetErrorString());
    if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) fail(path, "mesh file is incomplete");
    // A file Assimp had to repair (dropping faces, ignoring normals) is refused:
    // rendering what is left would hide the damage.
    if (!log.problems().empty()) {
        std::string all = log.problems().front();
        if (log.problems().size() > 1) all += " (and " + std::to_string(log.problems().size() - 1) + " more)";
        fail(path, "broken mesh, Assimp says: " + all);
    }

    const auto meshes = meshesOf(*scene);
    bool allNormals = true;
    bool allUvs = true;
    std::size_t vertexCount = 0;
    for (const aiMesh* m : meshes) {
        allNormals = allNormals && m->HasNormals();
        allUvs = allUvs && m->HasTextureCoords(0);
        vertexCount += m->mNumVertices;
    }
    std::size_t faceCount = 0;
    for (const aiMesh* m : meshes) faceCount += m->mNumFaces;
    if (vertexCount > kMaxMeshVertices)
        fail(path, "mesh has " + std::to_string(vertexCount) + " vertices, more than the limit of " +
                       std::to_string(kMaxMeshVertices));
    if (faceCount > kMaxMeshTriangles)
        fail(path, "mesh has " + std::to_string(faceCount) + " faces, more than the limit of " +
                       std::to_string(kMaxMeshTriangles) + " triangles");

    TriangleMesh mesh;
    mesh.positions.reserve(vertexCount);
    if (allNormals) mesh.normals.reserve(vertexCount);
    if (allUvs) mesh.uvs.reserve(vertexCount);
    for (const aiMesh* m : meshes) {
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        for (unsigned i = 0; i < m->mNumVertices; ++i) {
            const aiVector3D& p = m->mVertices[i];
            mesh.positions.emplace_back(p.x, p.y, p.z);
            if (allNormals) {
                const aiVector3D& n = m->mNormals[i];
                mesh.normals.emplace_back(n.x, n.y, n.z);
            }
            if (allUvs) {
                const aiVector3D& uv = m->mTextureCoords[0][i];
                mesh.uvs.push_back({uv.x, uv.y});
            }
        }
        for (unsigned f = 0; f < m->mNumFaces; ++f) {
            const aiFace& face = m->mFaces[f];
            // Triangulation leaves points and lines as they are; they have no area to hit.
            if (face.mNumIndices != 3) continue;
            mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
        }
    }
    if (mesh.triangles.empty()) fail(path, "mesh file contains no triangles");
    if (const std::string problem = validateMesh(mesh); !problem.empty()) fail(path, problem);
    return mesh;
}

}  // namespace raycache
