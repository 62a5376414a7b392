#pragma once
#include <iosfwd>

namespace raycache {

// `raycache scenes`: one line per built-in scene, name then description.
void runScenesCommand(std::ostream& out);

}  // namespace raycache
