#include "scene/MeshLoader.h"

#include <assimp/BaseImporter.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <set>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include "core/Errors.h"
#include "scene/AssimpLogCapture.h"
#include "scene/MeshLimits.h"
#include "scene/MeshRepair.h"
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

// "N of the file's M vertices are not finite (infinite or NaN)", or empty.
// Checked before post-processing: Assimp's joining of vertices sorts them
// by position, which NaN breaks.
std::string nonFiniteVertices(const aiScene& scene) {
    std::size_t bad = 0, all = 0;
    for (const aiMesh* m : meshesOf(scene)) {
        all += m->mNumVertices;
        for (unsigned i = 0; m->mVertices && i < m->mNumVertices; ++i) {
            const aiVector3D& p = m->mVertices[i];
            bad += (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) ? 0 : 1;
        }
    }
    if (bad == 0) return {};
    return std::to_string(bad) + " of the file's " + std::to_string(all) + " vertices are not finite (infinite or NaN)";
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
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(path, "mesh file not found");
    if (!std::filesystem::is_regular_file(path, ec)) fail(path, "not a regular file");
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (!ec && bytes > kMaxMeshFileBytes)
        fail(path, "mesh file is " + std::to_string(bytes) + " bytes, more than the limit of " +
                       std::to_string(kMaxMeshFileBytes));
    // What was repaired or ignored, in the order met, for the one note.
    std::vector<std::string> phrases;
    // Text formats Assimp reads leniently are checked strictly first.
    if (strictlyCheckedText(path)) {
        std::string accepted;
        if (const auto problem = checkMeshText(path, readText(path, ec ? 0 : bytes), &accepted))
            throw InputError(InputLocation{.file = path.string(), .line = problem->line, .column = problem->column},
                             problem->message);
        if (!accepted.empty()) phrases.push_back(accepted);
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
    if (const std::string problem = nonFiniteVertices(*scene); !problem.empty()) fail(path, problem);
    // Normals are made by our own rule (repairMesh), not by Assimp's
    // GenSmoothNormals: for a file that indexes its vertices that step
    // gives each vertex the normal of the last face written to it (all but
    // 59 289 of the dragon's 437 645), and a zero vector to a vertex of
    // degenerate faces only (NaN once a transform normalized it).
    // FindInvalidData is not used either: it drops a part's whole normal or
    // texture coordinate array for one bad value, and says nothing countable.
    unsigned steps = aiProcess_Triangulate | aiProcess_PreTransformVertices;
    if (cornersStoredApart(*scene)) steps |= aiProcess_JoinIdenticalVertices;
    scene = importer.ApplyPostProcessing(steps);
    if (!scene) fail(path, std::string("Assimp cannot read it: ") + importer.GetErrorString());
    if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) fail(path, "mesh file is incomplete");
    // A file Assimp had to repair (dropping faces, ignoring normals) is refused:
    // rendering what is left would hide the damage.
    if (!log.problems().empty()) {
        std::string all = log.problems().front();
        if (log.problems().size() > 1) all += " (and " + std::to_string(log.problems().size() - 1) + " more)";
        fail(path, "broken mesh, Assimp says: " + all);
    }
    if (!log.missingMaterialFiles().empty())
        phrases.push_back(std::string(log.missingMaterialFiles().size() == 1 ? "material file " : "material files ") +
                          joined(log.missingMaterialFiles(), ", ") + " not found; the object's material is used");

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
