#pragma once
// Versions of the libraries the scene loaders read files with, as loaded at
// run time (the shared libraries may be newer than the headers built against).
#include <string>

namespace raycache {

std::string assimpVersion();   // "5.2.5"
std::string openExrVersion();  // "3.1.5"

}  // namespace raycache
