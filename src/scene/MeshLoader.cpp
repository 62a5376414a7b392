#include "scene/MeshLoader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cstdint>
#include <fstream>
#include <limits>
#include <span>
#include <sstream>
#include <string>
#include <system_error>

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

std::span<const aiMesh* const> meshesOf(const aiScene& scene) {
    if (!scene.mMeshes) return {};
    return {scene.mMeshes, scene.mNumMeshes};
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

    // PreTransformVertices bakes the node hierarchy into the vertices, so the
    // meshes can simply be concatenated. Assimp's default logger is silent.
    Assimp::Importer importer;
    const AssimpLogCapture log;
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                           aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure | aiProcess_FindInvalidData;
    const aiScene* scene = importer.ReadFile(path.string(), flags);
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
