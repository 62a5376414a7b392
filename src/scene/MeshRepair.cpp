#include "scene/MeshRepair.h"

#include <algorithm>
#include <cmath>

#include "scene/VertexNormals.h"

namespace raycache {
namespace {

bool hasArea(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return false;
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    return length(cross(b - a, c - a)) > 0.0f;
}

// Zero-area triangles are never hit, but they are not harmless: their
// vertices' smooth normals came out NaN (the Stanford dragon's 108), and a
// mesh of nothing else draws nothing. Assimp's FindDegenerates is not used
// for this: with its area check it compares areas with an absolute 1e-6 (it
// kept 524 of the dragon's 871 414 triangles), without it it misses
// triangles whose three distinct corners lie on a line.
std::size_t dropDegenerateTriangles(TriangleMesh& mesh) {
    const std::size_t before = mesh.triangles.size();
    std::vector<std::array<std::uint32_t, 3>> kept;
    kept.reserve(before);
    for (const auto& t : mesh.triangles)
        if (hasArea(mesh, t)) kept.push_back(t);
    // A mesh of nothing but degenerate triangles stays as it is, for the
    // caller to refuse with the count.
    if (kept.empty() || kept.size() == before) return 0;
    mesh.triangles = std::move(kept);
    return before - mesh.triangles.size();
}

void repairNormals(TriangleMesh& mesh, const std::vector<bool>& normalMissing, MeshRepairs& repairs) {
    if (mesh.normals.empty()) {
        mesh.normals = smoothNormalsByPosition(mesh);
        return;
    }
    std::vector<bool> replace(mesh.normals.size(), false);
    bool any = false;
    for (std::size_t v = 0; v < mesh.normals.size(); ++v) {
        const Vec3& n = mesh.normals[v];
        const float l = length(n);
        if (!normalMissing.empty() && normalMissing[v])
            ++repairs.missingNormals;
        else if (!isFinite(n) || !std::isfinite(l))
            ++repairs.nonFiniteNormals;
        else if (!(l > 0.0f))
            ++repairs.zeroLengthNormals;
        else
            continue;
        replace[v] = any = true;
    }
    if (!any) return;
    // By vertex, not by position: a file with normals splits its vertices
    // where it wants a crease, and a repaired vertex keeps to its side.
    const std::vector<Vec3> made = areaWeightedNormals(mesh);
    for (std::size_t v = 0; v < mesh.normals.size(); ++v)
        if (replace[v]) mesh.normals[v] = made[v];
}

// Why the texture coordinates cannot be used, or empty.
std::string unusableUvs(const TriangleMesh& mesh) {
    std::size_t nonFinite = 0;
    for (const auto& uv : mesh.uvs) nonFinite += (std::isfinite(uv[0]) && std::isfinite(uv[1])) ? 0 : 1;
    if (nonFinite > 0) return std::to_string(nonFinite) + " of " + std::to_string(mesh.uvs.size()) + " not finite";
    const bool allSame = std::all_of(mesh.uvs.begin(), mesh.uvs.end(),
                                     [&](const std::array<float, 2>& uv) { return uv == mesh.uvs.front(); });
    if (mesh.uvs.size() > 1 && allSame) return "all " + std::to_string(mesh.uvs.size()) + " the same";
    return {};
}

// "1 triangle", "108 triangles".
std::string counted(std::size_t n, const std::string& singular, const std::string& plural) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

}  // namespace

std::vector<std::string> MeshRepairs::phrases() const {
    std::vector<std::string> out;
    if (degenerateTriangles > 0)
        out.push_back("dropped " + counted(degenerateTriangles, "degenerate triangle", "degenerate triangles") +
                      " of " + std::to_string(trianglesRead));
    const std::size_t normals = zeroLengthNormals + nonFiniteNormals + missingNormals;
    if (normals > 0) {
        std::vector<std::string> kinds;
        if (zeroLengthNormals > 0) kinds.push_back(std::to_string(zeroLengthNormals) + " zero-length");
        if (nonFiniteNormals > 0) kinds.push_back(std::to_string(nonFiniteNormals) + " not finite");
        if (missingNormals > 0) kinds.push_back(std::to_string(missingNormals) + " missing");
        std::string phrase = "regenerated ";
        if (kinds.size() == 1) {
            phrase += kinds.front() + (normals == 1 ? " normal of " : " normals of ") + std::to_string(vertices);
        } else {
            phrase += std::to_string(normals) + " invalid normals of " + std::to_string(vertices) + " (";
            for (std::size_t i = 0; i < kinds.size(); ++i) phrase += (i ? ", " : "") + kinds[i];
            phrase += ")";
        }
        out.push_back(phrase);
    }
    if (!ignoredUvs.empty()) out.push_back("ignored its texture coordinates (" + ignoredUvs + ")");
    return out;
}

MeshRepairs repairMesh(TriangleMesh& mesh, const std::vector<bool>& normalMissing) {
    MeshRepairs repairs;
    repairs.trianglesRead = mesh.triangles.size();
    repairs.vertices = mesh.positions.size();
    repairs.degenerateTriangles = dropDegenerateTriangles(mesh);
    repairNormals(mesh, normalMissing, repairs);
    repairs.ignoredUvs = unusableUvs(mesh);
    if (!repairs.ignoredUvs.empty()) mesh.uvs.clear();
    return repairs;
}

}  // namespace raycache
