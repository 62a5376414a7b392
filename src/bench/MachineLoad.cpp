#include "bench/MachineLoad.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
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

std::optional<ProcStatCpu> parseProcStatCpu(std::string_view text) {
    std::istringstream in{std::string(text)};
    std::optional<ProcStatCpu> result;
    int cpus = 0;
    for (std::string line; std::getline(in, line);) {
        std::istringstream fields(line);
        std::string name;
        fields >> name;
        if (name == "cpu") {
            // user nice system idle iowait irq softirq steal [guest guest_nice]
            std::uint64_t v[8] = {};
            int n = 0;
            while (n < 8 && fields >> v[n]) ++n;
            if (n < 4) return std::nullopt;  // older kernels stop after idle; fewer is not /proc/stat
            ProcStatCpu c;
            c.busyTicks = v[0] + v[1] + v[2] + v[5] + v[6] + v[7];
            c.idleTicks = v[3] + v[4];
            result = c;
        } else if (name.size() > 3 && name.rfind("cpu", 0) == 0 &&
                   name.find_first_not_of("0123456789", 3) == std::string::npos) {
            ++cpus;
        }
    }
    if (!result || cpus == 0) return std::nullopt;
    result->cpus = cpus;
    return result;
}

CpuSample currentCpuSample() {
    CpuSample s;
    s.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) == 0)
        s.ownSeconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    std::ifstream in("/proc/stat");
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    const long ticksPerSecond = sysconf(_SC_CLK_TCK);
    if (const std::optional<ProcStatCpu> c = parseProcStatCpu(text); c && ticksPerSecond > 0) {
        s.busySeconds = static_cast<double>(c->busyTicks) / static_cast<double>(ticksPerSecond);
        s.cpus = c->cpus;
    }
    return s;
}

double othersCpuShare(const CpuSample& start, const CpuSample& end) {
    if (!start.known() || !end.known()) return -1.0;
    const double wall = end.wallSeconds - start.wallSeconds;
    if (wall <= 0.0) return -1.0;
    const double others = (end.busySeconds - start.busySeconds) - (end.ownSeconds - start.ownSeconds);
    return std::clamp(others / (wall * end.cpus), 0.0, 1.0);
}

std::string formatOthersShare(double share) {
    if (share < 0.0) return "unknown";
    char b[32];
    std::snprintf(b, sizeof b, "%.0f %%", 100.0 * share);
    return b;
}

namespace {

std::string oneMinute(const LoadAverage& l) {
    if (!l.known()) return "unknown";
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", l.one);
    return b;
}

}  // namespace

std::string busyMachineWarning(double othersShare, const LoadAverage& before, const LoadAverage& after, int cpus) {
    if (othersShare <= kBusyOthersShare) return {};  // quiet, or unknown (negative)
    return "warning: the machine was busy (other processes used " + formatOthersShare(othersShare) + " of its " +
           std::to_string(cpus) + " CPUs' time meanwhile; load average " + oneMinute(before) + " before, " +
           oneMinute(after) + " after): times are slower and noisier than on a quiet machine";
}

}  // namespace raycache
