#include "bench/MachineLoad.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace raycache {

std::string LoadAverage::toString() const {
    if (!known()) return "unknown";
    char b[96];
    std::snprintf(b, sizeof b, "%.2f, %.2f, %.2f", one, five, fifteen);
    return b;
}

LoadAverage parseLoadAverage(std::string_view line) {
    std::istringstream in{std::string(line)};
    LoadAverage l;
    if (!(in >> l.one >> l.five >> l.fifteen) || l.one < 0.0 || l.five < 0.0 || l.fifteen < 0.0) return {};
    return l;
}

LoadAverage currentLoadAverage() {
    std::ifstream in("/proc/loadavg");
    std::string line;
    if (!std::getline(in, line)) return {};
    return parseLoadAverage(line);
}

std::string busyMachineWarning(const LoadAverage& before, const LoadAverage& after, int hardwareThreads,
                               int workerThreads) {
    if (hardwareThreads <= 0) return {};
    const double half = 0.5 * hardwareThreads;
    const bool busyBefore = before.known() && before.one >= half;
    const bool busyAfter = after.known() && after.one > workerThreads + half;
    if (!busyBefore && !busyAfter) return {};
    char b[256];
    std::snprintf(b, sizeof b,
                  "warning: the machine was busy (load average %.2f before, %.2f after, on %d hardware threads): "
                  "times are slower and noisier than on a quiet machine",
                  before.known() ? before.one : 0.0, after.known() ? after.one : 0.0, hardwareThreads);
    return b;
}

}  // namespace raycache
