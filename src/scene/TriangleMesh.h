#pragma once
// Indexed triangle mesh. `normals` and `uvs` are per vertex and either empty or
// the same length as `positions`.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/Transform.h"
#include "core/Vec3.h"

namespace raycache {

struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;
    std::vector<std::array<float, 2>> uvs;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

// The mesh with every vertex and normal mapped through `t`.
TriangleMesh transformed(const TriangleMesh& mesh, const Transform& t);

// "triangle T uses vertex V but the mesh has N vertices" for the first
// such triangle, else empty.
std::string indexOutOfRange(const TriangleMesh& mesh);

// Empty string if the mesh is usable, otherwise what is wrong with it
// (no triangles, index out of range, non-finite values, array size mismatch,
// only degenerate triangles).
std::string validateMesh(const TriangleMesh& mesh);

}  // namespace raycache
