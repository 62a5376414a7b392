#include "render/CameraRays.h"

#include <cmath>
#include <numbers>

namespace raycache {

CameraRays::CameraRays(const Camera& camera, int width, int height)
    : origin_(camera.position),
      invWidth_(1.0f / static_cast<float>(width)),
      invHeight_(1.0f / static_cast<float>(height)) {
    const float tanHalf = std::tan(0.5f * camera.verticalFovDeg * std::numbers::pi_v<float> / 180.0f);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    forward_ = normalize(camera.lookAt - camera.position);
    const Vec3 right = normalize(cross(forward_, camera.up));
    const Vec3 up = cross(right, forward_);
    right_ = right * (tanHalf * aspect);
    up_ = up * tanHalf;
    pixelSpread_ = tanHalf;
}

}  // namespace raycache
