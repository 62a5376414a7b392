#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "scene/Camera.h"
#include "scene/CameraPath.h"
#include "scene/Environment.h"
#include "scene/Light.h"
#include "scene/SceneObject.h"
#include "scene/SceneRenderDefaults.h"

namespace raycache {

// Most lights a scene may have: shading keeps per-light shadow queries in
// fixed arrays on the stack.
inline constexpr std::size_t kMaxLights = 64;

struct Scene {
    std::string name;
    std::vector<SceneObject> objects;  // object id = index here
    std::vector<Light> lights;
    Environment environment;
    Camera camera;           // the camera at frame 0
    CameraPath cameraPath;   // how it moves
    int defaultFrames = 1;   // length of the default camera path
    SceneRenderDefaults render;  // what the scene file asks for; command-line options win
};

}  // namespace raycache
