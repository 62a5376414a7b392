#pragma once
#include <string>

#include "scene/Scene.h"

namespace raycache {

// A built-in scene by name, or a JSON scene file by path. Throws InputError
// naming the argument when it is neither.
Scene loadScene(const std::string& builtinNameOrPath);

}  // namespace raycache
