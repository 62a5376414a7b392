#pragma once
// A regular expression (ECMAScript syntax, std::regex) for the tests that
// check text: compiled once, in TextPattern.cpp, rather than in every test
// batch that uses one, since <regex>'s templates cost a batch more compile
// time than its tests (docs/testing.md, "Where the time goes").

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace raycache::test {

class TextPattern {
public:
    explicit TextPattern(const std::string& pattern, bool ignoreCase = false);
    ~TextPattern();
    TextPattern(const TextPattern&) = delete;
    TextPattern& operator=(const TextPattern&) = delete;

    // Whether the whole text matches.
    bool matchesWhole(const std::string& text) const;
    // Whether the pattern occurs somewhere in the text.
    bool occursIn(const std::string& text) const;
    // The first match's groups (group 0 the whole match), or nothing when it does not occur.
    std::optional<std::vector<std::string>> firstMatch(const std::string& text) const;
    // Every match's groups, in order.
    std::vector<std::vector<std::string>> everyMatch(const std::string& text) const;

private:
    struct Compiled;
    std::unique_ptr<Compiled> compiled_;
};

}  // namespace raycache::test
