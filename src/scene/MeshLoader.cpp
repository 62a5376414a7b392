#include "scene/MeshLoader.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "scene/AssimpFileReader.h"
#include "scene/MeshLimits.h"
#include "scene/MeshRepair.h"

namespace raycache {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
    throw InputError(InputLocation{.file = path.string()}, message);
}

std::span<const aiMesh* const> meshesOf(const aiScene& scene) {
    if (!scene.mMeshes) return {};
    return {scene.mMeshes, scene.mNumMeshes};
}

// Whether the file stores every face corner as a vertex of its own (OBJ and
// STL, as Assimp reads them), rather than indexing shared vertices (PLY,
// OFF, glTF). Only the former are joined into shared vertices: joining the
// dragon's 437 645 vertices, already shared, cost 1.4 of the 1.9 s Assimp took, to
// find 2 101 repeated ones, and normals made by position need no joining.
bool cornersStoredApart(const aiScene& scene) {
    std::size_t vertices = 0, corners = 0;
    for (const aiMesh* m : meshesOf(scene)) {
        vertices += m->mNumVertices;
        for (unsigned f = 0; m->mFaces && f < m->mNumFaces; ++f) corners += m->mFaces[f].mNumIndices;
    }
    return vertices >= corners;
}

std::size_t trianglesOf(const aiMesh& m) {
    std::size_t n = 0;
    for (unsigned f = 0; m.mFaces && f < m.mNumFaces; ++f) n += m.mFaces[f].mNumIndices == 3 ? 1 : 0;
    return n;
}

std::string joined(const std::vector<std::string>& parts, const std::string& separator) {
    std::string out;
    for (std::size_t i = 0; i < parts.size(); ++i) out += (i ? separator : "") + parts[i];
    return out;
}

}  // namespace

LoadedMesh loadMeshFile(const std::filesystem::path& path) {
    AssimpFileReader reader(path);
    // Normals are made by our own rule (repairMesh), not by Assimp's
    // GenSmoothNormals: for a file that indexes its vertices that step
    // gives each vertex the normal of the last face written to it (all but
    // 59 289 of the dragon's 437 645), and a zero vector to a vertex of
    // degenerate faces only (NaN once a transform normalized it).
    // FindInvalidData is not used either: it drops a part's whole normal or
    // texture coordinate array for one bad value, and says nothing countable.
    // PreTransformVertices bakes the node hierarchy into the vertices, so the
    // meshes can simply be concatenated.
    unsigned steps = aiProcess_Triangulate | aiProcess_PreTransformVertices;
    if (cornersStoredApart(reader.scene())) steps |= aiProcess_JoinIdenticalVertices;
    const aiScene* scene = &reader.postProcess(steps);
    // What was repaired or ignored, in the order met, for the one note.
    std::vector<std::string> phrases = reader.acceptedPhrases();

    // Parts without triangles (points, lines) draw nothing: their vertices are left out.
    std::vector<const aiMesh*> parts;
    std::size_t otherPrimitives = 0;
    std::size_t vertexCount = 0;
    std::size_t faceCount = 0;
    bool anyNormals = false;
    bool allNormals = true;
    std::size_t partsWithUvs = 0;
    for (const aiMesh* m : meshesOf(*scene)) {
        const std::size_t triangles = trianglesOf(*m);
        otherPrimitives += m->mNumFaces - triangles;
        faceCount += m->mNumFaces;
        if (triangles == 0) continue;
        parts.push_back(m);
        vertexCount += m->mNumVertices;
        anyNormals = anyNormals || m->HasNormals();
        allNormals = allNormals && m->HasNormals();
        partsWithUvs += m->HasTextureCoords(0) ? 1 : 0;
    }
    if (vertexCount > kMaxMeshVertices)
        fail(path, "mesh has " + std::to_string(vertexCount) + " vertices, more than the limit of " +
                       std::to_string(kMaxMeshVertices));
    if (faceCount > kMaxMeshTriangles)
        fail(path, "mesh has " + std::to_string(faceCount) + " faces, more than the limit of " +
                       std::to_string(kMaxMeshTriangles) + " triangles");
    if (parts.empty()) fail(path, "mesh file contains no triangles");
    if (otherPrimitives > 0)
        phrases.push_back("ignored " + std::to_string(otherPrimitives) +
                          (otherPrimitives == 1 ? " point or line" : " points and lines") +
                          " (only triangles are drawn)");
    const bool allUvs = partsWithUvs == parts.size();
    if (partsWithUvs > 0 && !allUvs)
        phrases.push_back("ignored its texture coordinates (" + std::to_string(parts.size() - partsWithUvs) +
                          " of its " + std::to_string(parts.size()) + " parts " +
                          (parts.size() - partsWithUvs == 1 ? "has" : "have") + " none)");

    TriangleMesh mesh;
    std::vector<bool> normalMissing;  // vertices of parts without normals, when others have them
    mesh.positions.reserve(vertexCount);
    if (anyNormals) mesh.normals.reserve(vertexCount);
    if (anyNormals && !allNormals) normalMissing.reserve(vertexCount);
    if (allUvs) mesh.uvs.reserve(vertexCount);
    for (const aiMesh* m : parts) {
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        for (unsigned i = 0; i < m->mNumVertices; ++i) {
            const aiVector3D& p = m->mVertices[i];
            mesh.positions.emplace_back(p.x, p.y, p.z);
            if (anyNormals) {
                const aiVector3D n = m->HasNormals() ? m->mNormals[i] : aiVector3D();
                mesh.normals.emplace_back(n.x, n.y, n.z);
                if (!allNormals) normalMissing.push_back(!m->HasNormals());
            }
            if (allUvs) {
                const aiVector3D& uv = m->mTextureCoords[0][i];
                mesh.uvs.push_back({uv.x, uv.y});
            }
        }
        for (unsigned f = 0; f < m->mNumFaces; ++f) {
            const aiFace& face = m->mFaces[f];
            if (face.mNumIndices != 3) continue;
            mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
        }
    }
    // Assimp's validation has checked the indices; repairs index the vertices, so make sure.
    if (const std::string problem = indexOutOfRange(mesh); !problem.empty()) fail(path, problem);
    const MeshRepairs repairs = repairMesh(mesh, normalMissing);
    for (const std::string& phrase : repairs.phrases()) phrases.push_back(phrase);
    if (const std::string problem = validateMesh(mesh); !problem.empty()) fail(path, problem);
    LoadedMesh loaded{std::move(mesh), {}};
    if (!phrases.empty()) loaded.note = path.string() + ": " + joined(phrases, "; ");
    return loaded;
}

}  // namespace raycache
