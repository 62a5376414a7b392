#pragma once
// What a measurement was taken on and with: machine, build and library
// versions, recorded beside every result so figures can be compared honestly.
#include <string>

namespace raycache {

struct RunEnvironment {
    std::string cpuModel;     // from /proc/cpuinfo, "unknown" elsewhere
    int hardwareThreads = 0;  // std::thread::hardware_concurrency
    int workerThreads = 0;    // threads the renderer used
    std::string os;           // uname: system, release, machine
    std::string buildType;    // CMAKE_BUILD_TYPE
    std::string compiler;     // compiler name and version
    std::string gitCommit;    // commit at configure time, "unknown" outside a git checkout
    std::string raycacheVersion;
    std::string embreeVersion;
    std::string tbbVersion;
    std::string startedAt;    // UTC, ISO 8601
    std::string loadAverage;  // /proc/loadavg's 1, 5, 15 minute figures at the start: how busy the machine was
};

// Collects the environment of this process; `workerThreads` as the renderer runs.
RunEnvironment currentRunEnvironment(int workerThreads);

}  // namespace raycache
