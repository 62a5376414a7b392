#pragma once
// A glTF URI as a path: %XX escapes decoded (glTF URIs are RFC 3986). One
// rule for the scene loader's textures and the limits' buffer files.
#include <string>

namespace raycache {

std::string percentDecodedUri(const std::string& uri);

}  // namespace raycache
