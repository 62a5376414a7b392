#include <gtest/gtest.h>

#include <cmath>

#include "bench/MarkdownTable.h"
#include "core/Errors.h"

using namespace raycache;

TEST(MarkdownTable, HeaderSeparatorAndRows) {
    MarkdownTable t({"N", "speed-up"});
    t.addRow({"1", "1.02×"});
    t.addRow({"a|b", "x"});
    EXPECT_EQ(t.toMarkdown(), "| N | speed-up |\n| --- | --- |\n| 1 | 1.02× |\n| a\\|b | x |\n");
    EXPECT_EQ(t.rowCount(), 2u);
    EXPECT_THROW(t.addRow({"only one"}), InputError);
    EXPECT_THROW(MarkdownTable({}), InputError);
}

TEST(MarkdownTable, Cells) {
    EXPECT_EQ(cellNumber(1.234, 2), "1.23");
    EXPECT_EQ(cellNumber(std::nan(""), 2), "–");
    EXPECT_EQ(cellRange({12.0, 10.5, 15.25}, 1), "12.0 (10.5–15.2)");
}
