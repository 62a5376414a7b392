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

TEST(MachineLoad, QuietMachineGivesNoWarning) {
    // 2 hardware threads, the bench using both: ~2 afterwards is the bench itself.
    EXPECT_EQ(busyMachineWarning({0.3, 0.3, 0.3}, {2.4, 1.0, 0.5}, 2, 2), "");
    EXPECT_EQ(busyMachineWarning({}, {}, 2, 2), "");
}

TEST(MachineLoad, BusyBeforeOrAfterWarns) {
    const std::string before = busyMachineWarning({1.0, 1.0, 1.0}, {2.0, 1.0, 1.0}, 2, 2);
    EXPECT_EQ(before.rfind("warning: the machine was busy (load average 1.00 before, 2.00 after, on 2 hardware "
                           "threads)",
                           0),
              0u)
        << before;
    EXPECT_NE(busyMachineWarning({0.2, 0.2, 0.2}, {3.5, 2.0, 1.0}, 2, 2), "");  // others ran beside the bench
    EXPECT_EQ(busyMachineWarning({0.2, 0.2, 0.2}, {3.0, 2.0, 1.0}, 2, 2), "");  // just at the edge
}

}  // namespace
}  // namespace raycache
