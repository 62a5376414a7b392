#pragma once
// What a glTF material's data textures change at a hit besides the albedo
// (scene/Material.h): the metallic-roughness texture gives each hit its own
// metallic and roughness, the normal texture its shading normal. The wave's
// surface lanes carry the results (render/HitLanes.h), so direct light and
// secondary rays read them like any other lane.
#include <cstdint>

#include "render/HitLanes.h"
#include "render/SurfacePoint.h"
#include "scene/Material.h"
#include "scene/TriangleMesh.h"

namespace raycache {

// Lane k's metallic and roughness: the material's factors, times its
// metallic-roughness texture's blue and green at the lane's texture
// coordinates when it has one.
void materialFactorLane(const Material& material, int k, SurfaceLanes16& surfaces);
// materialFactorLane for the selected lanes.
void materialFactorLanes(const Material& material, const int* lanes, SurfaceLanes16& surfaces);

// The shading normal of a hit at `sp` (oriented as surfacePointAt orients
// it, texture coordinates set) on triangle `primitiveId` of `mesh`, with
// the material's normal texture applied: the texel (x, y scaled by
// normalScale, z) in the tangent frame whose tangent follows the texture's
// u and whose bitangent its v across the triangle, made orthogonal to the
// interpolated normal. A triangle whose texture coordinates are degenerate
// keeps its normal.
Vec3 normalFromTexture(const Material& material, const TriangleMesh& mesh, int primitiveId, const SurfacePoint& sp);

// normalFromTexture for the selected lanes, hits on `mesh`'s triangles
// `primitiveIds`; the lanes' normals are replaced.
void normalTextureLanes(const Material& material, const TriangleMesh& mesh, const std::uint32_t* primitiveIds,
                        const int* lanes, SurfaceLanes16& surfaces);

// The texture coordinates at `position` on triangle `primitiveId` of
// `mesh` (which has them): the G-buffer's hits carry a position, not
// barycentrics.
void triangleUvAt(const TriangleMesh& mesh, int primitiveId, const Vec3& position, float& u, float& v);

}  // namespace raycache
