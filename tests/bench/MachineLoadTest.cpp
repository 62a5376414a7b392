#include <gtest/gtest.h>

#include "bench/MachineLoad.h"

namespace raycache {
namespace {

TEST(MachineLoad, ParsesProcLoadavg) {
    const LoadAverage l = parseLoadAverage("0.52 1.25 10.00 3/412 98765\n");
    ASSERT_TRUE(l.known());
    EXPECT_DOUBLE_EQ(l.one, 0.52);
    EXPECT_DOUBLE_EQ(l.five, 1.25);
    EXPECT_DOUBLE_EQ(l.fifteen, 10.0);
    EXPECT_EQ(l.toString(), "0.52, 1.25, 10.00");
}

TEST(MachineLoad, GarbageIsUnknown) {
    EXPECT_FALSE(parseLoadAverage("").known());
    EXPECT_FALSE(parseLoadAverage("busy 1 2").known());
    EXPECT_FALSE(parseLoadAverage("-1 2 3").known());
    EXPECT_EQ(LoadAverage{}.toString(), "unknown");
}

// /proc/stat as Linux 6.1 writes it on 2 vCPUs (the numbers made up, the layout not).
constexpr const char* kProcStat =
    "cpu  10132153 290696 3202628 46320170 94836 0 7233 1500 0 0\n"
    "cpu0 1393353 11 1312634 5921378 16542 0 4562 700 0 0\n"
    "cpu1 1359722 2 303342 3964880 23106 0 1003 800 0 0\n"
    "intr 199292 1 9 0 0 0 0 0 0 0 0 0 0 0\n"
    "ctxt 38014093\n"
    "btime 1706000000\n"
    "processes 26190\n"
    "procs_running 2\n"
    "procs_blocked 0\n"
    "softirq 1234 0 1 2 3 4 5 6 7 8 9\n";

TEST(MachineLoad, ParsesTheCpuLineOfProcStat) {
    const std::optional<ProcStatCpu> c = parseProcStatCpu(kProcStat);
    ASSERT_TRUE(c);
    // user + nice + system + irq + softirq + steal; guest columns are inside user and nice.
    EXPECT_EQ(c->busyTicks, 10132153u + 290696u + 3202628u + 0u + 7233u + 1500u);
    EXPECT_EQ(c->idleTicks, 46320170u + 94836u);  // idle + iowait
    EXPECT_EQ(c->cpus, 2);
}

TEST(MachineLoad, ProcStatWithoutACpuLineIsUnknown) {
    EXPECT_FALSE(parseProcStatCpu(""));
    EXPECT_FALSE(parseProcStatCpu("intr 1 2 3\nctxt 4\n"));
    EXPECT_FALSE(parseProcStatCpu("cpu  1 2\ncpu0 1 2\n"));    // too few fields
    EXPECT_FALSE(parseProcStatCpu("cpu  1 2 3 4 5 6 7 8\n"));  // no per-CPU lines: no count
    EXPECT_FALSE(parseProcStatCpu("cpu  x y z w\ncpu0 1 2 3 4\n"));
}

TEST(MachineLoad, ThisMachineHasCpuCounters) {
    const CpuSample s = currentCpuSample();
    EXPECT_TRUE(s.known()) << "Linux has /proc/stat and getrusage";
    EXPECT_GT(s.cpus, 0);
}

CpuSample sample(double wall, double busy, double own, int cpus = 2) {
    return {.wallSeconds = wall, .busySeconds = busy, .ownSeconds = own, .cpus = cpus};
}

TEST(MachineLoad, OthersShareIsBusyTimeNotOursOverTheMachine) {
    // 10 s on 2 CPUs = 20 CPU-seconds; the bench used 19, the machine 20: others 1, 5 %.
    EXPECT_DOUBLE_EQ(othersCpuShare(sample(100, 500, 40), sample(110, 520, 59)), 0.05);
    // The bench alone, both cores busy: nobody else.
    EXPECT_DOUBLE_EQ(othersCpuShare(sample(0, 1000, 0), sample(10, 1020, 20)), 0.0);
    // Another build on one core of two while the bench used one: half the machine.
    EXPECT_DOUBLE_EQ(othersCpuShare(sample(0, 0, 0), sample(10, 20, 10)), 0.5);
    // 4 CPUs: others 6 of 40 CPU-seconds.
    EXPECT_DOUBLE_EQ(othersCpuShare(sample(0, 0, 0, 4), sample(10, 14, 8, 4)), 0.15);
}

TEST(MachineLoad, OthersShareIsClampedAndUnknownWithoutCounters) {
    // /proc/stat's 10 ms ticks can trail getrusage: slightly negative reads as 0.
    EXPECT_DOUBLE_EQ(othersCpuShare(sample(0, 0, 0), sample(10, 19.98, 20)), 0.0);
    EXPECT_DOUBLE_EQ(othersCpuShare(sample(0, 0, 0), sample(1, 5, 0)), 1.0);
    EXPECT_LT(othersCpuShare(sample(0, -1, 0), sample(10, 20, 10)), 0.0);
    EXPECT_LT(othersCpuShare(sample(0, 0, 0), sample(10, 20, -1)), 0.0);
    EXPECT_LT(othersCpuShare(sample(0, 0, 0, 0), sample(10, 20, 10, 0)), 0.0);
    EXPECT_LT(othersCpuShare(sample(5, 0, 0), sample(5, 20, 10)), 0.0);  // no time passed
}

TEST(MachineLoad, QuietMachineGivesNoWarningWhateverItsLoadAverage) {
    // The case that used to warn: load 1.53 before, left by the bench's own previous experiment.
    EXPECT_EQ(busyMachineWarning(0.02, {1.53, 1.2, 0.9}, {2.1, 1.5, 1.0}, 2), "");
    EXPECT_EQ(busyMachineWarning(kBusyOthersShare, {}, {}, 2), "") << "at the edge";
    EXPECT_EQ(busyMachineWarning(-1.0, {9.0, 9.0, 9.0}, {9.0, 9.0, 9.0}, 2), "") << "unknown";
}

TEST(MachineLoad, OthersUsingMoreThanATenthWarn) {
    const std::string w = busyMachineWarning(0.234, {1.0, 1.0, 1.0}, {2.5, 1.0, 1.0}, 2);
    EXPECT_EQ(w,
              "warning: the machine was busy (other processes used 23 % of its 2 CPUs' time meanwhile; load average "
              "1.00 before, 2.50 after): times are slower and noisier than on a quiet machine");
    EXPECT_NE(busyMachineWarning(0.11, {}, {}, 2).find("load average unknown before, unknown after"),
              std::string::npos);
    EXPECT_EQ(formatOthersShare(-1.0), "unknown");
    EXPECT_EQ(formatOthersShare(0.0), "0 %");
}

}  // namespace
}  // namespace raycache
