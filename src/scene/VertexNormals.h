#pragma once
// Vertex normals made from a mesh's triangles: the one rule raycache uses
// wherever it needs normals a file did not give (or gave broken), and for
// meshes that deform.
#include <vector>

#include "scene/TriangleMesh.h"

namespace raycache {

// One unit normal per vertex: the sum of the cross products of the triangles
// that use the vertex (so each triangle weighs by its area, and zero-area
// triangles add nothing), normalized. Never non-finite: a vertex whose sum
// vanishes (triangles that cancel) or overflows takes the normal of its
// largest triangle, and a vertex no triangle with area uses (never shaded)
// takes +y.
std::vector<Vec3> areaWeightedNormals(const TriangleMesh& mesh);

// The same, but vertices at exactly the same position count as one: their
// triangles are summed together and they share the result. Files split a
// vertex where its texture coordinates differ, or repeat it; without
// normals of their own saying where the creases are, the surface is smooth
// across such splits. The positions must be finite (NaN has no place in
// the order that finds equal positions; the loader refuses such files).
std::vector<Vec3> smoothNormalsByPosition(const TriangleMesh& mesh);

}  // namespace raycache
