#pragma once
// How busy the machine was around a measurement. Timings taken while other
// work competes for the cores are slower and noisier than the code is; the
// bench records the load average before and after and says so when it was high.
#include <string>
#include <string_view>

namespace raycache {

struct LoadAverage {
    double one = -1.0;  // 1, 5 and 15 minute load averages; negative = unknown
    double five = -1.0;
    double fifteen = -1.0;

    bool known() const { return one >= 0.0; }
    // "1.23, 0.98, 0.50", or "unknown".
    std::string toString() const;
};

// The first three fields of a /proc/loadavg line; unknown if they are not numbers.
LoadAverage parseLoadAverage(std::string_view procLoadavgLine);
// This machine's, from /proc/loadavg; unknown elsewhere.
LoadAverage currentLoadAverage();

// Empty when the machine looked quiet, otherwise a one-line warning. Busy:
// the 1-minute load before was at least half the hardware threads (others
// were already running), or after it exceeded the bench's own worker threads
// by half the hardware threads (others ran beside it).
std::string busyMachineWarning(const LoadAverage& before, const LoadAverage& after, int hardwareThreads,
                               int workerThreads);

}  // namespace raycache
