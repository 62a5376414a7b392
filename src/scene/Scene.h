#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "scene/Animation.h"
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
    SceneAnimation animation;  // objects and lights that move; empty for a still scene
    float fps = 30.0f;         // frame index / fps = the time a frame shows
    SceneRenderDefaults render;  // what the scene file asks for; command-line options win
    // What loading repaired or ignored, one line per file that needed it
    // ("<mesh file>: dropped 108 degenerate triangles of 871414"), in the
    // order the files were read; the commands print each as "note: …".
    std::vector<std::string> notes;
};

}  // namespace raycache
