#include "rendercache/SampleRetexturing.h"

#include "render/HitOnPrimitive.h"
#include "render/SurfacePoint.h"

namespace raycache {

bool retexturedColor(const SceneObject& object, int objectId, const SampleTexturing& texturing, const Ray& centreRay,
                     float sampleDistance, Rgb& color) {
    const auto hit = hitOnPrimitive(object, objectId, texturing.primitiveId, centreRay, sampleDistance);
    if (!hit) return false;
    color = albedoAtHit(object, centreRay, *hit) * texturing.lighting + texturing.rest;
    return true;
}

void CentreRetexturing::prepare(const SceneObject& object, int objectId, int primitiveId) {
    object_ = objectId;
    const TriangleMesh& mesh = *std::get<MeshShape>(object.shape).mesh;
    triangle_.primitive = primitiveId;
    triangle_.plane = TriangleOnItsPlane(mesh, primitiveId);
    triangle_.hasUvs = triangle_.plane.valid && !mesh.uvs.empty();
    if (!triangle_.hasUvs) return;
    const auto& tri = mesh.triangles[static_cast<std::size_t>(primitiveId)];
    for (std::size_t corner = 0; corner < 3; ++corner) triangle_.uv[corner] = mesh.uvs[tri[corner]];
}

}  // namespace raycache
