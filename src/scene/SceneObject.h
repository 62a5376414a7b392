#pragma once
#include <memory>
#include <string>
#include <variant>

#include "core/Transform.h"
#include "core/Vec3.h"
#include "scene/Material.h"
#include "scene/TriangleMesh.h"

namespace raycache {

// Analytic sphere in world space.
struct Sphere {
    Vec3 center;
    float radius = 1.0f;
};

// Triangle mesh already placed in world space (instance transforms are baked
// in when the scene is built, so the tracer sees one flat level).
struct MeshShape {
    std::shared_ptr<const TriangleMesh> mesh;
};

struct SceneObject {
    std::string name;
    std::variant<Sphere, MeshShape> shape;
    Material material;
    // The object's origin in world space: the centre of its caching cube. The
    // cube follows the object's translation, never its rotation.
    Vec3 origin;
    // For an animated object: the keyframed transform that placed its rest
    // shape at the current time (scene/Animation.h); identity otherwise.
    Transform placement;
};

}  // namespace raycache
