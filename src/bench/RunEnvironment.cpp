#include "bench/RunEnvironment.h"

#include <sys/utsname.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

namespace raycache {

namespace {

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) != 0) continue;
        const auto colon = line.find(':');
        if (colon == std::string::npos) continue;
        std::string value = line.substr(colon + 1);
        value.erase(0, value.find_first_not_of(" \t"));
        return value;
    }
    return "unknown";
}

std::string loadAverage() {
    std::ifstream in("/proc/loadavg");
    double one = 0, five = 0, fifteen = 0;
    if (!(in >> one >> five >> fifteen)) return "unknown";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.2f, %.2f, %.2f", one, five, fifteen);
    return buffer;
}

std::string utcNow() {
    const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    gmtime_r(&t, &tm);
    char buffer[32];
    std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return buffer;
}

}  // namespace

RunEnvironment currentRunEnvironment(int workerThreads) {
    RunEnvironment e;
    e.cpuModel = cpuModel();
    e.hardwareThreads = static_cast<int>(std::thread::hardware_concurrency());
    e.workerThreads = workerThreads;
    utsname u{};
    if (uname(&u) == 0) e.os = std::string(u.sysname) + " " + u.release + " " + u.machine;
    e.build = currentBuildInfo();
    e.startedAt = utcNow();
    e.loadAverage = loadAverage();
    return e;
}

}  // namespace raycache
