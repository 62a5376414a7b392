#pragma once
// The viewer's interactive camera: orbit about a target (drag), fly (WASD +
// mouse look), zoom (dolly toward the target). Angles are measured about the
// scene camera's up vector, so scenes with any up direction work.
#include "scene/Camera.h"

namespace raycache {

class ViewerCamera {
public:
    // Starts at `camera`, looking at its lookAt point.
    explicit ViewerCamera(const Camera& camera);

    // Takes over `camera` (e.g. where a camera path stopped), keeping the up vector.
    void setCamera(const Camera& camera);
    Camera camera() const;

    // Moves the camera about the target, degrees: yaw > 0 to its right
    // (about up), pitch > 0 upward. Pitch stops short of the poles.
    void orbit(float yawDegrees, float pitchDegrees);
    // Turns the view direction about the camera position (mouse look),
    // degrees: yaw > 0 to the right, pitch > 0 up. The target moves with it.
    void look(float yawDegrees, float pitchDegrees);
    // Moves camera and target together: forward along the view direction,
    // right, and up along the up vector; scene units.
    void fly(float forward, float right, float up);
    // Dollies toward the target: distance *= factor (> 0), never closer than
    // a small fraction of the starting distance.
    void zoom(float factor);

    float distance() const { return distance_; }
    const Vec3& target() const { return target_; }

private:
    Vec3 forward() const;  // unit vector from camera to target

    Vec3 up_, east_, north_;  // orthonormal basis: up_ and two horizontal axes
    Vec3 target_;
    float distance_ = 1.0f;
    float yaw_ = 0.0f;    // radians about up_, 0 looking along -north_
    float pitch_ = 0.0f;  // radians, positive looking up
    float fovDeg_ = 45.0f;
    float minDistance_ = 1e-3f;
};

}  // namespace raycache
