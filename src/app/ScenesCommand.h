#pragma once
#include <iosfwd>

#include "scene/MeshSearchPath.h"

namespace raycache {

// `raycache scenes`: one line per built-in scene, name then description; the
// scenes made of real meshes (scene/RealMeshScenes.h) last, each whose mesh
// file is not on `meshes` marked unavailable with what to do about it.
void runScenesCommand(std::ostream& out, const MeshSearchPath& meshes);
// The same with the meshes on meshSearchPathFromEnvironment().
void runScenesCommand(std::ostream& out);

}  // namespace raycache
