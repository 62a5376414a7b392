#pragma once
// Loading a scene from a JSON scene file. The format is documented in
// docs/scene-format.md.
#include <filesystem>

#include "scene/Scene.h"

namespace raycache {

// Reads, validates and builds the scene in `path`. Mesh and image paths in the
// file are relative to the file's own directory. Any problem with the file or
// with a file it references throws InputError with a one-line message of the
// form "<file>:<line>:<col>: <json pointer>: <what>".
Scene loadSceneFile(const std::filesystem::path& path);

}  // namespace raycache
