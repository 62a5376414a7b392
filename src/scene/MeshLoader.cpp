#include "scene/MeshLoader.h"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <system_error>

#include "core/Errors.h"

namespace raycache {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
    throw InputError(InputLocation{.file = path.string()}, message);
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

    // PreTransformVertices bakes the node hierarchy into the vertices, so the
    // meshes can simply be concatenated. Assimp's default logger is silent.
    Assimp::Importer importer;
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                           aiProcess_GenSmoothNormals | aiProcess_PreTransformVertices |
                           aiProcess_ValidateDataStructure | aiProcess_FindInvalidData;
    const aiScene* scene = importer.ReadFile(path.string(), flags);
    if (!scene) fail(path, std::string("cannot load mesh: ") + importer.GetErrorString());
    if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) fail(path, "mesh file is incomplete");

    const auto meshes = meshesOf(*scene);
    bool allNormals = true;
    bool allUvs = true;
    std::size_t vertexCount = 0;
    for (const aiMesh* m : meshes) {
        allNormals = allNormals && m->HasNormals();
        allUvs = allUvs && m->HasTextureCoords(0);
        vertexCount += m->mNumVertices;
    }
    if (vertexCount > std::numeric_limits<std::uint32_t>::max())
        fail(path, "mesh has more than 2^32 vertices");

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
            mesh.triangles.push_back(
                {base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
        }
    }
    if (mesh.triangles.empty()) fail(path, "mesh file contains no triangles");
    if (const std::string problem = validateMesh(mesh); !problem.empty()) fail(path, problem);
    return mesh;
}

}  // namespace raycache
