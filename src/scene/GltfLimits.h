#pragma once
// The limits a glTF file's JSON must keep (docs/scene-format.md, "Limits"),
// checked before Assimp reads the file: its glTF readers recurse down the
// node tree (a 20 000-deep chain of nodes overflowed the stack), copy every
// placement of a node that has two parents, and trust the sizes the JSON
// states (buffer lengths, accessor counts and strides, sparse accessors).
// Far beyond what real scenes hold, low enough that a wrong or hostile file
// is refused before it costs gigabytes or the process.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>

#include "scene/MeshLimits.h"

namespace raycache {

// Levels of the node tree, a root node being level 1. Assimp 5.2's glTF 2.0
// reader recurses once per level: this limit keeps it far below where the
// default stack overflows (docs/log/2026-11-28-fuzz-findings.md, "glTF node
// depth"), while skeletons and CAD assemblies stay below a few hundred.
inline constexpr std::size_t kMaxGltfNodeDepth = 1024;
inline constexpr std::size_t kMaxGltfNodes = 200000;  // twice the objects a scene may have
inline constexpr std::size_t kMaxGltfMeshes = 100000;  // as many as a scene's objects
inline constexpr std::size_t kMaxGltfAccessors = 1000000;
inline constexpr std::size_t kMaxGltfBufferViews = 1000000;
inline constexpr std::size_t kMaxGltfBuffers = 10000;
inline constexpr std::size_t kMaxGltfImages = 10000;  // as many as a scene's materials
// Elements of one accessor: the indices of the most triangles a mesh may have.
inline constexpr std::uint64_t kMaxGltfAccessorElements = 3 * std::uint64_t{kMaxMeshTriangles};
// All buffers together (and an accessor's zeros when it has no buffer view):
// the most vertices and triangles a mesh may have, with normals and texture
// coordinates, take 880 MB.
inline constexpr std::uint64_t kMaxGltfBufferBytes = std::uint64_t{1} << 30;

// Where a glTF file keeps its binary data, as far as the checks need it.
struct GltfFileLayout {
    bool binary = false;                // a binary glTF (GLB)
    std::uint64_t binaryChunkBytes = 0;  // the length of its BIN chunk, 0 without one
};

// Checks the parsed JSON of the glTF file at `path` (2.0, or 1.0's node
// graph and counts): the counts above, the node graph (GltfNodeGraph.h),
// every buffer's byteLength against the data it names and the limit, every
// buffer view within its buffer, every accessor's elements within its buffer
// view (strides and sparse parts included). Throws InputError naming the
// file and the JSON pointer of the field at fault, one line.
void checkGltfLimits(const std::filesystem::path& path, const nlohmann::json& root, const GltfFileLayout& layout);

}  // namespace raycache
