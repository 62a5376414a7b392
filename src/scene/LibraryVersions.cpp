#include "scene/LibraryVersions.h"

#include <assimp/version.h>
#include <openexr.h>

namespace raycache {

std::string assimpVersion() {
    return std::to_string(aiGetVersionMajor()) + "." + std::to_string(aiGetVersionMinor()) + "." +
           std::to_string(aiGetVersionPatch());
}

std::string openExrVersion() {
    int major = 0, minor = 0, patch = 0;
    const char* extra = nullptr;
    exr_get_library_version(&major, &minor, &patch, &extra);
    return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch) + (extra ? extra : "");
}

}  // namespace raycache
