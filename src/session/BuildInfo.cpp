#include "session/BuildInfo.h"

#include "core/LaneInstructionSet.h"
#include "core/Parallel.h"
#include "scene/LibraryVersions.h"
#include "trace/EmbreeDeviceConfig.h"
#include "trace/EmbreeVersion.h"

// Generated at every build by cmake/GitCommit.cmake; the other two are
// defined for this file by src/CMakeLists.txt.
#include "GitCommit.h"
#ifndef RAYCACHE_BUILD_TYPE
#define RAYCACHE_BUILD_TYPE "unknown"
#endif
#ifndef RAYCACHE_VERSION
#define RAYCACHE_VERSION "unknown"
#endif

namespace raycache {

namespace {

std::string compilerName() {
#if defined(__clang__)
    return std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
    return std::string("g++ ") + __VERSION__;
#else
    return "unknown";
#endif
}

}  // namespace

BuildInfo currentBuildInfo() {
    BuildInfo b;
    b.raycacheVersion = RAYCACHE_VERSION;
    b.gitCommit = RAYCACHE_GIT_COMMIT;
    b.buildType = RAYCACHE_BUILD_TYPE;
    b.compiler = compilerName();
    b.embreeVersion = embreeVersion();
    b.embreeInstructions = embreeInstructionSet();
    b.tbbVersion = Parallel::libraryVersion();
    b.assimpVersion = assimpVersion();
    b.openExrVersion = openExrVersion();
    b.lanes = laneInstructionSet();
    b.baselineLanesBuild = builtWithBaselineLanes();
    return b;
}

std::string formatBuildInfo(const BuildInfo& b) {
    return "raycache " + b.raycacheVersion + "\n" +
           "commit: " + b.gitCommit + "\n" +
           "build: " + b.buildType + ", " + b.compiler + "\n" +
           "Embree: " + b.embreeVersion + "\n" +
           "Embree instructions: " + b.embreeInstructions + "\n" +
           "oneTBB: " + b.tbbVersion + "\n" +
           "Assimp: " + b.assimpVersion + "\n" +
           "OpenEXR: " + b.openExrVersion + "\n" +
           "lanes: " + b.lanes;
}

}  // namespace raycache
