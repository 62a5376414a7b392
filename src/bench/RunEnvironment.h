#pragma once
// What a measurement was taken on and with: machine, build and library
// versions, recorded beside every result so figures can be compared honestly.
#include <string>

#include "session/BuildInfo.h"

namespace raycache {

struct RunEnvironment {
    std::string cpuModel;     // from /proc/cpuinfo, "unknown" elsewhere
    int hardwareThreads = 0;  // std::thread::hardware_concurrency
    int workerThreads = 0;    // threads the renderer used
    std::string os;           // uname: system, release, machine
    BuildInfo build;          // what ran: version, commit, build, libraries, lanes
    std::string startedAt;    // UTC, ISO 8601
    std::string loadAverage;  // /proc/loadavg's 1, 5, 15 minute figures at the start: how busy the machine was
};

// Collects the environment of this process; `workerThreads` as the renderer runs.
RunEnvironment currentRunEnvironment(int workerThreads);

}  // namespace raycache
