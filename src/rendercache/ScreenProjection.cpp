#include "rendercache/ScreenProjection.h"

#include <cmath>
#include <numbers>

namespace raycache {

ScreenProjection::ScreenProjection(const Camera& camera, int width, int height)
    : eye_(camera.position),
      halfWidth_(0.5f * static_cast<float>(width)),
      halfHeight_(0.5f * static_cast<float>(height)) {
    // The same axes CameraRays builds its rays from.
    const float tanHalf = std::tan(0.5f * camera.verticalFovDeg * std::numbers::pi_v<float> / 180.0f);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    forward_ = normalize(camera.lookAt - camera.position);
    const Vec3 right = normalize(cross(forward_, camera.up));
    const Vec3 up = cross(right, forward_);
    right_ = right * (1.0f / (tanHalf * aspect));
    up_ = up * (1.0f / tanHalf);
}

}  // namespace raycache
