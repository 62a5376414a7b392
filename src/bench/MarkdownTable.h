#pragma once
// GitHub-flavoured Markdown tables, built row by row.
#include <string>
#include <vector>

#include "core/SampleSummary.h"

namespace raycache {

// Cell text: `value` with `decimals` digits after the point, "–" if not finite.
std::string cellNumber(double value, int decimals);
// Cell text: "median (min–max)".
std::string cellRange(const SampleSummary& s, int decimals);

class MarkdownTable {
public:
    explicit MarkdownTable(std::vector<std::string> headers);

    // Appends a row; throws InputError unless it has one cell per header.
    void addRow(std::vector<std::string> cells);
    std::size_t rowCount() const { return rows_.size(); }

    // Header, separator and rows, one line each, '|' in cells escaped.
    std::string toMarkdown() const;

private:
    std::vector<std::string> headers_;
    std::vector<std::vector<std::string>> rows_;
};

}  // namespace raycache
