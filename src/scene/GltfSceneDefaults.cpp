#include "scene/GltfSceneDefaults.h"

#include <cmath>
#include <numbers>

namespace raycache {

Camera cameraFramingBounds(const Box3& bounds) {
    Camera c;
    c.verticalFovDeg = 45.0f;
    const Vec3 centre = (bounds.lo + bounds.hi) * 0.5f;
    // A flat or point-like scene still gets a camera some way off.
    const float radius = std::fmax(0.5f * length(bounds.hi - bounds.lo), 1e-3f);
    const float halfFov = 0.5f * c.verticalFovDeg * std::numbers::pi_v<float> / 180.0f;
    const float distance = 1.1f * radius / std::sin(halfFov);
    c.lookAt = centre;
    c.position = centre + normalize(Vec3{0.4f, 0.3f, 1.0f}) * distance;
    c.up = {0.0f, 1.0f, 0.0f};
    return c;
}

Light lightOverTheShoulder(const Camera& camera) {
    const Vec3 forward = normalize(camera.lookAt - camera.position);
    const Vec3 right = normalize(cross(forward, camera.up));
    const Vec3 up = cross(right, forward);
    Light l;
    l.type = LightType::Directional;
    l.direction = normalize(forward - up * 0.5f + right * 0.3f);
    l.intensity = Rgb(1.0f);
    return l;
}

}  // namespace raycache
