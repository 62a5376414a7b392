#include <gtest/gtest.h>

#include <sstream>

#include "core/ProgressBar.h"

using namespace raycache;

TEST(ProgressBar, PlainLinesWithoutControlCharactersWhenNotATerminal) {
    std::ostringstream out;
    double now = 0.0;
    ProgressBar bar(out, false, 10.0, [&] { return now; });
    bar.step("table-5.1: behind-0");
    bar.advance(5.0);
    bar.step("table-5.1: behind-1");
    bar.note("a finding");
    bar.finish();
    EXPECT_EQ(out.str(), "[  0%] table-5.1: behind-0\n[ 50%] table-5.1: behind-1\na finding\n");
}

TEST(ProgressBar, TerminalBarShowsShareAndEta) {
    std::ostringstream out;
    double now = 0.0;
    ProgressBar bar(out, true, 10.0, [&] { return now; });
    bar.step("work");
    EXPECT_LT(bar.etaSeconds(), 0.0);  // unknown before any work is done
    now = 10.0;
    bar.advance(4.0);
    // 40 % in 10 s: 15 s left.
    EXPECT_DOUBLE_EQ(bar.etaSeconds(), 15.0);
    const std::string s = out.str();
    EXPECT_NE(s.find('\r'), std::string::npos);
    EXPECT_NE(s.find(" 40% "), std::string::npos);
    EXPECT_NE(s.find("ETA 15s"), std::string::npos);
    EXPECT_NE(s.find("############"), std::string::npos);  // 12 of 30 cells
    bar.note("line");
    EXPECT_NE(out.str().find("\r\033[Kline\n"), std::string::npos);  // the bar is cleared before a line
}

TEST(ProgressBar, DurationsAndClamping) {
    EXPECT_EQ(ProgressBar::formatDuration(42.4), "42s");
    EXPECT_EQ(ProgressBar::formatDuration(65), "1m05s");
    EXPECT_EQ(ProgressBar::formatDuration(7380), "2h03m");
    EXPECT_EQ(ProgressBar::formatDuration(-3), "0s");
    std::ostringstream out;
    ProgressBar bar(out, false, 2.0, [] { return 0.0; });
    bar.advance(5.0);
    EXPECT_DOUBLE_EQ(bar.fractionDone(), 1.0);
}
