#include "viewer/ViewerCamera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace raycache {

namespace {

constexpr float kRadiansPerDegree = std::numbers::pi_v<float> / 180.0f;
constexpr float kMaxPitch = 89.0f * kRadiansPerDegree;

// Any unit vector perpendicular to `n` (unit).
Vec3 perpendicular(const Vec3& n) {
    const Vec3 a = std::fabs(n.x) < 0.9f ? Vec3{1.0f, 0.0f, 0.0f} : Vec3{0.0f, 1.0f, 0.0f};
    return normalize(cross(n, a));
}

}  // namespace

ViewerCamera::ViewerCamera(const Camera& camera) {
    up_ = normalize(camera.up);
    // North: the horizontal part of the starting view direction, so a yaw of
    // zero is the scene's own view.
    Vec3 f = camera.lookAt - camera.position;
    Vec3 horizontal = f - up_ * dot(f, up_);
    north_ = length(horizontal) > 1e-6f ? -normalize(horizontal) : perpendicular(up_);
    east_ = cross(up_, north_);
    setCamera(camera);
    minDistance_ = std::max(1e-3f, distance_ * 1e-3f);
}

void ViewerCamera::setCamera(const Camera& camera) {
    Vec3 f = camera.lookAt - camera.position;
    distance_ = std::max(length(f), 1e-3f);
    f = f * (1.0f / distance_);
    target_ = camera.lookAt;
    pitch_ = std::clamp(std::asin(std::clamp(dot(f, up_), -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    // f's horizontal part = -(cos yaw * north + sin yaw * east) * cos pitch
    yaw_ = std::atan2(-dot(f, east_), -dot(f, north_));
    fovDeg_ = camera.verticalFovDeg;
}

Vec3 ViewerCamera::forward() const {
    const float c = std::cos(pitch_);
    return -(north_ * std::cos(yaw_) + east_ * std::sin(yaw_)) * c + up_ * std::sin(pitch_);
}

Camera ViewerCamera::camera() const {
    Camera c;
    c.lookAt = target_;
    c.position = target_ - forward() * distance_;
    c.up = up_;
    c.verticalFovDeg = fovDeg_;
    return c;
}

void ViewerCamera::orbit(float yawDegrees, float pitchDegrees) {
    // A larger yaw puts the camera further toward east_, its right-hand side.
    yaw_ += yawDegrees * kRadiansPerDegree;
    pitch_ = std::clamp(pitch_ - pitchDegrees * kRadiansPerDegree, -kMaxPitch, kMaxPitch);
}

void ViewerCamera::look(float yawDegrees, float pitchDegrees) {
    const Vec3 position = target_ - forward() * distance_;
    yaw_ -= yawDegrees * kRadiansPerDegree;  // forward turns toward the camera's right
    pitch_ = std::clamp(pitch_ + pitchDegrees * kRadiansPerDegree, -kMaxPitch, kMaxPitch);
    target_ = position + forward() * distance_;
}

void ViewerCamera::fly(float forwardAmount, float right, float upAmount) {
    const Vec3 f = forward();
    const Vec3 r = normalize(cross(f, up_));
    target_ += f * forwardAmount + r * right + up_ * upAmount;
}

void ViewerCamera::zoom(float factor) {
    if (!(factor > 0.0f) || !std::isfinite(factor)) return;
    distance_ = std::max(distance_ * factor, minDistance_);
}

}  // namespace raycache
