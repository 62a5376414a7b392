#pragma once
// The repairs of mesh trouble that spoils only an attribute, not the
// geometry (docs/scene-format.md, "Meshes: what is refused, what is
// repaired"): triangles without area dropped, broken normals made again
// from the triangles, unusable texture coordinates ignored. Each repair is
// counted, so that the loader's one note can say what was done.
#include <cstddef>
#include <string>
#include <vector>

#include "scene/TriangleMesh.h"

namespace raycache {

struct MeshRepairs {
    std::size_t trianglesRead = 0;        // before any was dropped
    std::size_t degenerateTriangles = 0;  // dropped: zero area, or a vertex used twice
    std::size_t vertices = 0;
    // Normals made again from the triangles, by what was wrong with them.
    std::size_t zeroLengthNormals = 0;
    std::size_t nonFiniteNormals = 0;
    std::size_t missingNormals = 0;  // vertices of a part without normals, in a file whose other parts have them
    std::string ignoredUvs;          // why the texture coordinates were dropped, or empty

    // What was done, one phrase per kind of repair, in a fixed order (e.g.
    // "dropped 108 degenerate triangles of 871414"); empty if nothing was.
    std::vector<std::string> phrases() const;
};

// Repairs `mesh` in place; its positions must be finite and its indices in
// range (what breaks the geometry is the loader's to refuse first).
// - Triangles with no area (repeated index, or zero cross product) are
//   dropped, unless all are: the caller refuses such a mesh.
// - Without normals, every vertex gets smoothNormalsByPosition's. With
//   normals, those that are zero-length, not finite or marked in
//   `normalMissing` (empty, or one flag per vertex) are replaced by
//   areaWeightedNormals'; the others are kept as given.
// - Texture coordinates with a non-finite value, or all the same (a
//   placeholder: a texture would show one texel), are dropped.
MeshRepairs repairMesh(TriangleMesh& mesh, const std::vector<bool>& normalMissing = {});

}  // namespace raycache
