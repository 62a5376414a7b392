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
    primitive_ = primitiveId;
    const TriangleMesh& mesh = *std::get<MeshShape>(object.shape).mesh;
    valid_ = primitiveId >= 0 && static_cast<std::size_t>(primitiveId) < mesh.triangles.size();
    if (!valid_) return;
    const auto& tri = mesh.triangles[static_cast<std::size_t>(primitiveId)];
    p0_ = mesh.positions[tri[0]];
    e1_ = mesh.positions[tri[1]] - p0_;
    e2_ = mesh.positions[tri[2]] - p0_;
    edgeOn_ = 1e-7f * length(e1_) * length(e2_);
    hasUvs_ = !mesh.uvs.empty();
    if (hasUvs_)
        for (int corner = 0; corner < 3; ++corner) uv_[static_cast<std::size_t>(corner)] = mesh.uvs[tri[static_cast<std::size_t>(corner)]];
}

}  // namespace raycache
