#pragma once
// A scene at one moment of its animation.
#include <vector>

#include "scene/Scene.h"

namespace raycache {

// What differs between two poses of a scene.
struct SceneChanges {
    std::vector<int> objects;  // object indices whose shape, placement or origin changed
    std::vector<int> lights;   // light indices whose position, direction or intensity changed

    bool empty() const { return objects.empty() && lights.empty(); }
};

// Puts `posed` (a copy of `scene`, or an earlier pose of it) into the pose
// at `time` and lists what changed from the pose it held. Still objects and
// lights are never touched, so references to them stay valid.
SceneChanges poseScene(const Scene& scene, float time, Scene& posed);

// The rest shape of an animated object after its deformation at `time` and
// its placement: the world-space shape that `poseScene` gives the object.
std::variant<Sphere, MeshShape> posedShape(const ObjectAnimation& animation, float time, const Transform& placement);

}  // namespace raycache
