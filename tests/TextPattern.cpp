#include "TextPattern.h"

#include <regex>

namespace raycache::test {

struct TextPattern::Compiled {
    std::regex regex;
};

TextPattern::TextPattern(const std::string& pattern, bool ignoreCase)
    : compiled_(std::make_unique<Compiled>(Compiled{
          std::regex(pattern, ignoreCase ? std::regex::ECMAScript | std::regex::icase : std::regex::ECMAScript)})) {}

TextPattern::~TextPattern() = default;

bool TextPattern::matchesWhole(const std::string& text) const {
    return std::regex_match(text, compiled_->regex);
}

bool TextPattern::occursIn(const std::string& text) const {
    return std::regex_search(text, compiled_->regex);
}

namespace {

std::vector<std::string> groupsOf(const std::smatch& match) {
    std::vector<std::string> groups;
    for (const auto& group : match) groups.push_back(group.str());
    return groups;
}

}  // namespace

std::optional<std::vector<std::string>> TextPattern::firstMatch(const std::string& text) const {
    std::smatch match;
    if (!std::regex_search(text, match, compiled_->regex)) return std::nullopt;
    return groupsOf(match);
}

std::vector<std::vector<std::string>> TextPattern::everyMatch(const std::string& text) const {
    std::vector<std::vector<std::string>> found;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), compiled_->regex); it != std::sregex_iterator(); ++it)
        found.push_back(groupsOf(*it));
    return found;
}

}  // namespace raycache::test
