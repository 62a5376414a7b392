#include "scene/TriangleMesh.h"

#include <algorithm>

namespace raycache {

TriangleMesh transformed(const TriangleMesh& mesh, const Transform& t) {
    TriangleMesh out = mesh;
    for (Vec3& p : out.positions) p = t.applyToPoint(p);
    for (Vec3& n : out.normals) n = normalize(t.applyToNormal(n));
    if (t.determinant() < 0.0f) {
        // A mirroring transform flips winding; restore counter-clockwise fronts.
        for (auto& tri : out.triangles) std::swap(tri[1], tri[2]);
    }
    return out;
}

std::string indexOutOfRange(const TriangleMesh& mesh) {
    const auto count = static_cast<std::uint32_t>(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        for (std::uint32_t idx : mesh.triangles[i])
            if (idx >= count)
                return "triangle " + std::to_string(i) + " uses vertex " + std::to_string(idx) + " but the mesh has " +
                       std::to_string(count) + " vertices";
    return {};
}

std::string validateMesh(const TriangleMesh& mesh) {
    if (mesh.triangles.empty()) return "mesh has no triangles";
    if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
        return "mesh has " + std::to_string(mesh.normals.size()) + " normals for " +
               std::to_string(mesh.positions.size()) + " vertices";
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size())
        return "mesh has " + std::to_string(mesh.uvs.size()) + " texture coordinates for " +
               std::to_string(mesh.positions.size()) + " vertices";
    for (const Vec3& p : mesh.positions)
        if (!isFinite(p)) return "mesh has a non-finite vertex position";
    for (const Vec3& n : mesh.normals)
        if (!isFinite(n)) return "mesh has a non-finite normal";
    if (std::string problem = indexOutOfRange(mesh); !problem.empty()) return problem;
    // Degenerate triangles among others are harmless (never hit); a mesh of
    // nothing else is invisible, which is never what was meant.
    const auto hasArea = [&](const std::array<std::uint32_t, 3>& t) {
        const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
        return length(cross(b - a, c - a)) > 0.0f;
    };
    if (std::none_of(mesh.triangles.begin(), mesh.triangles.end(), hasArea))
        return "all " + std::to_string(mesh.triangles.size()) + " triangles are degenerate (zero area)";
    return {};
}

}  // namespace raycache
