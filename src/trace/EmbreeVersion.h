#pragma once
#include <string>

namespace raycache {

// The Embree version raycache was built against ("3.13.5"), for reports.
std::string embreeVersion();

}  // namespace raycache
