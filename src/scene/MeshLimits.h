#pragma once
// Size limits of mesh input (docs/scene-format.md, "Limits"): far beyond the
// meshes a real-time scene uses, low enough that a wrong file is refused
// before it costs gigabytes of memory or minutes of BVH building.
#include <cstddef>
#include <cstdint>

namespace raycache {

inline constexpr std::uintmax_t kMaxMeshFileBytes = 512u << 20;
inline constexpr std::size_t kMaxMeshVertices = 20'000'000;
inline constexpr std::size_t kMaxMeshTriangles = 20'000'000;
// Any world coordinate of a sphere's bounds or a mesh vertex: beyond this,
// float positions are too coarse to trace against (a ulp near 1e7 is 1) and
// bounds like 3e38 + 3e38 overflow to infinity.
inline constexpr float kMaxWorldCoordinate = 1e7f;

}  // namespace raycache
