#pragma once
// A small well-formedness check for the SVG the bench writes: every tag is
// closed in order, attributes are quoted, text has no raw '<' or '&' outside
// entities. Not a full XML parser; enough to catch broken output.
#include <string>
#include <vector>

namespace raycache::test {

// Empty when well-formed, else what is wrong and where.
inline std::string xmlProblem(const std::string& text) {
    std::vector<std::string> open;
    std::size_t i = 0;
    int roots = 0;
    while (i < text.size()) {
        if (text[i] == '&') {
            const std::size_t semi = text.find(';', i);
            if (semi == std::string::npos || semi - i > 8) return "bare '&' at " + std::to_string(i);
            i = semi + 1;
            continue;
        }
        if (text[i] != '<') {
            if (text[i] == '>') return "bare '>' at " + std::to_string(i);
            ++i;
            continue;
        }
        const std::size_t end = text.find('>', i);
        if (end == std::string::npos) return "unterminated tag at " + std::to_string(i);
        std::string tag = text.substr(i + 1, end - i - 1);
        i = end + 1;
        if (tag.empty()) return "empty tag";
        if (tag.front() == '?') {
            if (tag.back() != '?') return "bad processing instruction";
            continue;
        }
        // Attribute values must be quoted and must not contain '<'.
        int quotes = 0;
        for (char c : tag) {
            if (c == '"') ++quotes;
            if (c == '<') return "'<' inside tag " + tag;
        }
        if (quotes % 2 != 0) return "unbalanced quotes in tag " + tag;
        if (tag.front() == '/') {
            const std::string name = tag.substr(1);
            if (open.empty() || open.back() != name)
                return "closing </" + name + "> does not match <" + (open.empty() ? "" : open.back()) + ">";
            open.pop_back();
            continue;
        }
        const bool selfClosing = tag.back() == '/';
        const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
        if (open.empty()) ++roots;
        if (!selfClosing) open.push_back(name);
    }
    if (!open.empty()) return "unclosed <" + open.back() + ">";
    if (roots != 1) return "expected one root element, found " + std::to_string(roots);
    return "";
}

inline int countOccurrences(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + what.size())) ++n;
    return n;
}

}  // namespace raycache::test
