#pragma once
// How busy the machine was around a measurement. Timings taken while other
// work competes for the cores are slower and noisier than the code is. The
// bench measures the CPU time *other* processes used while it ran (the whole
// machine's busy time from /proc/stat minus its own), warns when that was
// more than a tenth of the machine, and records the load averages beside it.
// The load average alone cannot say who was busy: the 1-minute figure before
// an experiment still holds the bench's own previous experiment.
#include <cstdint>
#include <optional>
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

// The "cpu" line of /proc/stat: time all CPUs spent, summed, in clock ticks
// (USER_HZ) since boot.
struct ProcStatCpu {
    std::uint64_t busyTicks = 0;  // user + nice + system + irq + softirq + steal
    std::uint64_t idleTicks = 0;  // idle + iowait
    int cpus = 0;                 // "cpuN" lines: the CPUs the sums run over
};
// Parses /proc/stat text; nullopt without a well-formed "cpu" line. Steal
// (time the hypervisor gave this VM's CPUs to others) counts as busy: for a
// timing it is CPU taken by someone else, just like another process. guest
// and guest_nice are already inside user and nice, so they are not added.
std::optional<ProcStatCpu> parseProcStatCpu(std::string_view procStatText);

// One reading of the counters others' CPU use is computed from.
struct CpuSample {
    double wallSeconds = 0.0;   // a steady clock
    double busySeconds = -1.0;  // the machine's busy CPU time, all CPUs summed; negative = unknown
    double ownSeconds = -1.0;   // this process's user + system CPU time, all its threads; negative = unknown
    int cpus = 0;               // CPUs busySeconds sums over

    bool known() const { return busySeconds >= 0.0 && ownSeconds >= 0.0 && cpus > 0; }
};
// Now, from /proc/stat and getrusage(RUSAGE_SELF); busy time unknown where
// /proc/stat cannot be read.
CpuSample currentCpuSample();

// The share of the machine's CPU time, in [0, 1], that other processes used
// between the two samples: (busy - own) / (wall x CPUs), clamped to [0, 1]
// (/proc/stat counts in 10 ms ticks, getrusage more finely, so a quiet
// machine can come out slightly negative). Negative when unknown: a sample
// unknown, no CPUs, or no wall time between the samples.
double othersCpuShare(const CpuSample& start, const CpuSample& end);

// The share above which the machine counts as busy: others used more than a
// tenth of its CPU time (0.2 of a core on 2 cores; a quiet machine's daemons
// use well under 1 %). Enough to slow a measurement bound to every core by
// about as much as the ±5 % the adaptive rounds aim for, twice over.
inline constexpr double kBusyOthersShare = 0.10;

// "12 %" or "unknown".
std::string formatOthersShare(double share);

// Empty when the machine looked quiet (others used at most kBusyOthersShare
// of it, or their use is unknown), otherwise a one-line warning naming their
// share and, for the record, the 1-minute load averages before and after.
std::string busyMachineWarning(double othersShare, const LoadAverage& before, const LoadAverage& after, int cpus);

}  // namespace raycache
