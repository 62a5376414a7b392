#pragma once
// Reads triangle meshes (OBJ, glTF 2.0 .gltf/.glb, PLY and whatever else Assimp
// understands) into one TriangleMesh, with one policy for trouble
// (docs/scene-format.md, "Meshes: what is refused, what is repaired"): what
// makes the geometry untrustworthy is refused, what spoils only an
// attribute is repaired and said so in one note.
#include <filesystem>
#include <string>

#include "scene/TriangleMesh.h"

namespace raycache {

struct LoadedMesh {
    TriangleMesh mesh;
    // What was repaired or ignored to load the file, as one line naming it
    // ("<file>: dropped 108 degenerate triangles of 871414; ..."); empty
    // when the file loaded as written. The same file gives the same note.
    std::string note;
};

// All meshes of the file, with their node transforms applied, merged into one.
// Faces are triangulated; points and lines are left out. Every vertex has a
// normal: the file's, or, where the file has none or a broken one, one made
// from the triangles (scene/VertexNormals.h). Texture coordinates (channel 0)
// are kept only if every part of the file has usable ones. Throws InputError
// naming the file if it is missing, cannot be parsed, has no triangles (or
// only degenerate ones), or breaks the geometry (indices out of range,
// non-finite vertices, truncated data).
LoadedMesh loadMeshFile(const std::filesystem::path& path);

}  // namespace raycache
