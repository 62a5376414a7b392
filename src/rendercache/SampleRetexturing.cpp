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

}  // namespace raycache
