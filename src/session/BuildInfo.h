#pragma once
// What this program is and what it was built with, gathered in one place for
// `raycache --version`, the statistics of `raycache render --stats` and the
// bench reports, so that all three say the same.
#include <string>

namespace raycache {

struct BuildInfo {
    std::string raycacheVersion;      // the CMake project version
    std::string gitCommit;            // at build time, "-dirty" with uncommitted changes; "unknown" outside git
    std::string buildType;            // CMAKE_BUILD_TYPE
    std::string compiler;             // compiler name and version
    std::string embreeVersion;        // built against
    std::string embreeInstructions;   // what Embree may use here (trace/EmbreeDeviceConfig.h)
    std::string tbbVersion;           // loaded
    std::string assimpVersion;        // loaded
    std::string openExrVersion;       // loaded
    std::string lanes;                // the lane code's instruction set here (core/LaneInstructionSet.h)
    bool baselineLanesBuild = false;  // built with RAYCACHE_BASELINE_LANES
};

BuildInfo currentBuildInfo();

// The lines `raycache --version` prints, without a final newline.
std::string formatBuildInfo(const BuildInfo& build);

}  // namespace raycache
