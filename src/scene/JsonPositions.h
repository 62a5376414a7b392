#pragma once
// Where each value of a JSON text starts, keyed by JSON pointer (RFC 6901).
// nlohmann::json keeps no source positions, so errors found while reading a
// parsed document would otherwise not be able to name a line and column.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace raycache {

struct TextPosition {
    int line = 0;    // 1-based, 0 = unknown
    int column = 0;  // 1-based, counted in characters (UTF-8 code points); 0 = unknown

    bool known() const { return line > 0; }
};

// The first thing that makes a text not (acceptable) JSON.
struct JsonSyntaxError {
    TextPosition position;
    std::string pointer;  // the value being read when it happened ("" = the root)
    std::string message;  // one line, without position or pointer
};

class JsonPositions {
public:
    // Indexes `text`. Indexing stops at the first syntax error, which also
    // covers numbers that overflow a double and duplicate member names.
    explicit JsonPositions(std::string_view text);

    const std::optional<JsonSyntaxError>& syntaxError() const { return syntaxError_; }

    // Where the value at `pointer` starts; unknown pointers give an unknown position.
    TextPosition valueAt(const std::string& pointer) const;
    // Where the member name of `pointer` starts when it is an object member,
    // otherwise where its value starts.
    TextPosition keyAt(const std::string& pointer) const;

    // 0-based byte offset -> 1-based line and column.
    TextPosition positionOf(std::size_t offset) const;

private:
    std::string text_;                      // kept to count columns in characters
    std::vector<std::size_t> lineStarts_;   // byte offset of each line's first character
    std::unordered_map<std::string, std::size_t> valueOffsets_;
    std::unordered_map<std::string, std::size_t> keyOffsets_;
    std::optional<JsonSyntaxError> syntaxError_;
};

// `parent` extended by one reference token, escaped as RFC 6901 requires.
std::string appendJsonPointer(const std::string& parent, std::string_view token);

}  // namespace raycache
