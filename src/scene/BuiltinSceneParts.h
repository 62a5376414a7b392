#pragma once
// The materials, objects, lights and camera paths the built-in scenes are
// made of (docs/builtin-scenes.md, "Materials used by the built-in scenes"),
// shared by the scenes that need no files (scene/BuiltinScenes.h) and those
// built around real meshes (scene/RealMeshScenes.h) so that a mirror is the
// same mirror in both.
#include <string>

#include "scene/Camera.h"
#include "scene/CameraPath.h"
#include "scene/Light.h"
#include "scene/Material.h"
#include "scene/SceneObject.h"
#include "scene/TriangleMesh.h"

namespace raycache::builtin {

// The constant environment of every built-in scene.
inline const Rgb kSky{0.35f, 0.45f, 0.65f};

// Distinct, saturated colors for sets of objects; repeats every 8.
Rgb paletteColor(int i);

// Mirror, glass and matte as the table in docs/builtin-scenes.md gives them;
// mirrors and glass cache their secondary rays (CCT, 512² faces).
Material mirror(const Rgb& tint = Rgb{0.1f}, float kr = 0.8f);
Material glass();
Material matte(const Rgb& color);
// A matte checkerboard with `squaresPerUnit` squares per texture-coordinate unit.
Material checker(const Rgb& even, const Rgb& odd, float squaresPerUnit);

SceneObject sphere(std::string name, const Vec3& center, float radius, Material material);
// `mesh` scaled, turned about y and moved to `at`, which is also its origin.
SceneObject meshObject(std::string name, const TriangleMesh& mesh, const Vec3& at, const Vec3& scale, float yawDeg,
                       Material material);
// Checkerboard floor: a square of side `size` at height y, squares 1 unit wide.
SceneObject floorObject(float size, float y = 0.0f);
// Upright square of side `size` centred at `center`, facing +z.
SceneObject wallObject(std::string name, const Vec3& center, float size, Material material);

Light pointLight(const Vec3& position, float intensity = 1.0f);
Camera camera(const Vec3& position, const Vec3& lookAt, float fov);
// The camera circling `center` about the world y axis.
CameraPath orbit(const Vec3& center, float degreesPerFrame);

}  // namespace raycache::builtin
