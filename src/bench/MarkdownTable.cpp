#include "bench/MarkdownTable.h"

#include <cmath>
#include <cstdio>

#include "core/Errors.h"
#include "core/TextFormat.h"

namespace raycache {

std::string cellNumber(double value, int decimals) {
    if (!std::isfinite(value)) return "–";
    return formatFixed(value, decimals);
}

std::string cellRange(const SampleSummary& s, int decimals) {
    return cellNumber(s.median, decimals) + " (" + cellNumber(s.min, decimals) + "–" + cellNumber(s.max, decimals) +
           ")";
}

namespace {

std::string cell(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '|')
            out += "\\|";
        else if (c == '\n')
            out += ' ';
        else
            out += c;
    }
    return out;
}

std::string line(const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const std::string& c : cells) s += " " + cell(c) + " |";
    return s + "\n";
}

}  // namespace

MarkdownTable::MarkdownTable(std::vector<std::string> headers) : headers_(std::move(headers)) {
    if (headers_.empty()) throw InputError("a Markdown table needs at least one column");
}

void MarkdownTable::addRow(std::vector<std::string> cells) {
    if (cells.size() != headers_.size())
        throw InputError("Markdown table row has " + std::to_string(cells.size()) + " cells, expected " +
                         std::to_string(headers_.size()));
    rows_.push_back(std::move(cells));
}

std::string MarkdownTable::toMarkdown() const {
    std::string s = line(headers_) + "|";
    for (std::size_t i = 0; i < headers_.size(); ++i) s += " --- |";
    s += "\n";
    for (const auto& row : rows_) s += line(row);
    return s;
}

}  // namespace raycache
