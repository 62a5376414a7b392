#pragma once
// How the camera moves from frame to frame.
#include <array>
#include <vector>

#include "scene/Camera.h"

namespace raycache {

enum class CameraPathKind {
    Static,     // every frame uses the base camera
    Orbit,      // the camera position circles `center` about the world y axis
    Pan,        // the camera stays put and turns (yaws) about the world y axis
    Keyframes,  // linear interpolation through a list of cameras
};
// Every kind, in the order messages list them.
inline constexpr std::array kCameraPathKinds{CameraPathKind::Static, CameraPathKind::Orbit, CameraPathKind::Pan,
                                             CameraPathKind::Keyframes};

// The name a kind has in scene files ("type") and on the command line.
constexpr const char* cameraPathKindName(CameraPathKind kind) {
    switch (kind) {
        case CameraPathKind::Static: return "static";
        case CameraPathKind::Orbit: return "orbit";
        case CameraPathKind::Pan: return "pan";
        case CameraPathKind::Keyframes: return "keyframes";
    }
    return "static";
}

struct CameraPath {
    CameraPathKind kind = CameraPathKind::Static;
    Vec3 center{0.0f, 0.0f, 0.0f};   // orbit centre
    float degreesPerFrame = 2.0f;     // orbit and pan step
    std::vector<Camera> keyframes;    // at least 2 for Keyframes
    int framesPerSegment = 10;        // frames from one keyframe to the next

    // The camera for frame `frame` (0-based) starting from `base`.
    Camera cameraAt(const Camera& base, int frame) const;
};

}  // namespace raycache
