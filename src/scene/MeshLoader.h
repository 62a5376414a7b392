#pragma once
// Reads triangle meshes (OBJ, glTF 2.0 .gltf/.glb, PLY and whatever else Assimp
// understands) into one TriangleMesh.
#include <filesystem>

#include "scene/TriangleMesh.h"

namespace raycache {

// All meshes of the file, with their node transforms applied, merged into one.
// Faces are triangulated; smooth normals are generated where the file has none.
// Normals and texture coordinates (channel 0) are kept only if every mesh in
// the file has them. Throws InputError naming the file if it is missing, cannot
// be parsed, has no triangles or fails validateMesh.
TriangleMesh loadMeshFile(const std::filesystem::path& path);

}  // namespace raycache
