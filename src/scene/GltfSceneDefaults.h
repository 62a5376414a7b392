#pragma once
// What a glTF scene gets where the file says nothing (docs/scene-format.md,
// "glTF 2.0 scenes"): a camera framed on the scene, a light from behind
// the camera, and a sky, since glTF has no background.
#include "core/Box3.h"
#include "core/Rgb.h"
#include "scene/Camera.h"
#include "scene/Light.h"

namespace raycache {

// What rays that leave a glTF scene see: black. A glTF file carries no
// environment (Blender's exporter writes none), and Blender renders such a
// scene with no world light as black.
inline constexpr Rgb kGltfBackground{0.0f, 0.0f, 0.0f};

// A 45° camera looking at the centre of `bounds` from the front (glTF's
// +z), a little to the right and above: from the direction (0.4, 0.3, 1),
// far enough that the bounding sphere fills the height of the view with a
// tenth to spare. `bounds` must not be empty.
Camera cameraFramingBounds(const Box3& bounds);

// A white directional light of intensity 1 that comes over the camera's
// left shoulder: it travels along f - 0.5 u + 0.3 r, normalized, with f,
// u and r the camera's forward, up and right directions.
Light lightOverTheShoulder(const Camera& camera);

}  // namespace raycache
