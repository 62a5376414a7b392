#include "scene/MeshTextCheck.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <vector>

namespace raycache {
namespace {

struct Token {
    std::string_view text;
    int column = 0;
};

// One logical line: its number and its tokens, comments removed.
struct Line {
    int number = 0;
    std::vector<Token> tokens;
};

// Splits into lines of whitespace-separated tokens, dropping '#' comments and
// lines left empty. OBJ's '\' continuation joins a line with the next.
std::vector<Line> tokenize(std::string_view text, bool continuation) {
    std::vector<Line> lines;
    Line current;
    int number = 1;
    std::size_t i = 0;
    bool joining = false;
    while (i <= text.size()) {
        const std::size_t end = std::min(text.find('\n', i), text.size());
        std::string_view line = text.substr(i, end - i);
        if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
        bool continues = false;
        if (continuation) {
            std::size_t last = line.find_last_not_of(" \t\r");
            if (last != std::string_view::npos && line[last] == '\\') {
                continues = true;
                line = line.substr(0, last);
            }
        }
        if (!joining) current = Line{number, {}};
        std::size_t p = 0;
        while (p < line.size()) {
            while (p < line.size() && std::isspace(static_cast<unsigned char>(line[p]))) ++p;
            const std::size_t start = p;
            while (p < line.size() && !std::isspace(static_cast<unsigned char>(line[p]))) ++p;
            if (p > start) current.tokens.push_back({line.substr(start, p - start), static_cast<int>(start) + 1});
        }
        joining = continues;
        if (!joining && !current.tokens.empty()) lines.push_back(std::move(current));
        if (end == text.size()) break;
        i = end + 1;
        ++number;
    }
    if (joining && !current.tokens.empty()) lines.push_back(std::move(current));
    return lines;
}

bool isNumber(std::string_view s) {
    double v = 0.0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

std::optional<std::int64_t> integer(std::string_view s) {
    std::int64_t v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
    return v;
}

MeshTextProblem problem(const Line& line, const Token& token, std::string message) {
    return {line.number, token.column, std::move(message)};
}

// At most `bytes` of the file's text, control characters shown as '?': it
// ends up in one line on a terminal.
std::string quoted(std::string_view s, std::size_t bytes = 40) {
    std::string text(s.substr(0, bytes));
    for (char& c : text)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return "\"" + text + "\"";
}

// A whole header line for a note: up to 60 bytes, trailing blanks left
// out, "..." where it is cut.
std::string quotedLine(std::string_view line) {
    line = line.substr(0, line.find_last_not_of(" \t") + 1);
    return line.size() > 60 ? quoted(line, 57).insert(58, "...") : quoted(line, 60);
}

// Statements Assimp accepts but that carry no triangle data we read
// (grouping, smoothing, materials, free-form geometry).
constexpr std::array<std::string_view, 27> kObjOtherStatements = {
    "o",    "g",    "s",    "usemtl", "mtllib", "l",     "p",        "vp",       "cstype",
    "deg",  "bmat", "step", "curv",   "curv2",  "surf",  "parm",     "trim",     "hole",
    "scrv", "sp",   "end",  "con",    "mg",     "bevel", "c_interp", "d_interp", "lod"};

}  // namespace

std::optional<MeshTextProblem> checkObjText(std::string_view text) {
    const std::vector<Line> lines = tokenize(text, true);
    // References may point forward (readers resolve them after reading the
    // file), so count everything first.
    std::int64_t total[3] = {0, 0, 0};  // v, vt, vn
    for (const Line& l : lines) {
        const std::string_view k = l.tokens[0].text;
        if (k == "v")
            ++total[0];
        else if (k == "vt")
            ++total[1];
        else if (k == "vn")
            ++total[2];
    }
    constexpr std::array<std::string_view, 3> kWhat = {"vertex", "texture coordinate", "normal"};
    std::int64_t seen[3] = {0, 0, 0};
    for (const Line& l : lines) {
        const std::string_view k = l.tokens[0].text;
        const std::size_t args = l.tokens.size() - 1;
        if (k == "v" || k == "vt" || k == "vn") {
            const int kind = k == "v" ? 0 : k == "vt" ? 1 : 2;
            const std::size_t lo = kind == 1 ? 1 : 3, hi = kind == 0 ? 7 : 3;
            if (args < lo || args > hi)
                return problem(l, l.tokens[0],
                               "\"" + std::string(k) + "\" needs " +
                                   (lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi)) +
                                   " numbers, got " + std::to_string(args));
            for (std::size_t i = 1; i < l.tokens.size(); ++i)
                if (!isNumber(l.tokens[i].text))
                    return problem(l, l.tokens[i], quoted(l.tokens[i].text) + " is not a number");
            ++seen[kind];
        } else if (k == "f") {
            if (args < 3)
                return problem(l, l.tokens[0], "a face needs at least 3 vertices, got " + std::to_string(args));
            for (std::size_t i = 1; i < l.tokens.size(); ++i) {
                const Token& t = l.tokens[i];
                // v, v/vt, v//vn or v/vt/vn
                std::array<std::string_view, 3> parts{};
                std::size_t count = 0, start = 0;
                for (std::size_t p = 0; p <= t.text.size(); ++p) {
                    if (p == t.text.size() || t.text[p] == '/') {
                        if (count == 3) return problem(l, t, quoted(t.text) + " is not a face vertex (v/vt/vn)");
                        parts[count++] = t.text.substr(start, p - start);
                        start = p + 1;
                    }
                }
                for (std::size_t kind = 0; kind < count; ++kind) {
                    if (kind > 0 && parts[kind].empty()) continue;  // "v//vn"
                    const std::optional<std::int64_t> idx = integer(parts[kind]);
                    if (!idx || *idx == 0)
                        return problem(l, t, quoted(t.text) + " is not a face vertex (v/vt/vn with indices from 1)");
                    // Negative indices count back from the last one read so far.
                    const std::int64_t resolved = *idx < 0 ? seen[kind] + *idx + 1 : *idx;
                    if (resolved < 1 || resolved > total[kind])
                        return problem(l, t,
                                       "face refers to " + std::string(kWhat[kind]) + " " + std::to_string(*idx) +
                                           " but the file has " + std::to_string(total[kind]));
                }
            }
        } else if (std::find(kObjOtherStatements.begin(), kObjOtherStatements.end(), k) == kObjOtherStatements.end()) {
            return problem(l, l.tokens[0], "unknown OBJ statement " + quoted(k));
        }
    }
    return std::nullopt;
}

std::optional<MeshTextProblem> checkOffText(std::string_view text) {
    const std::vector<Line> lines = tokenize(text, false);
    if (lines.empty()) return MeshTextProblem{1, 1, "empty OFF file"};
    const Line& header = lines[0];
    const std::string_view magic = header.tokens[0].text;
    constexpr std::array<std::string_view, 4> kMagics = {"OFF", "COFF", "NOFF", "CNOFF"};
    if (std::find(kMagics.begin(), kMagics.end(), magic) == kMagics.end())
        return problem(header, header.tokens[0], "OFF file does not start with OFF, COFF, NOFF or CNOFF");
    const std::size_t vertexNumbers = magic.find('N') != std::string_view::npos ? 6 : 3;
    const bool colors = magic.front() == 'C';

    // The counts may follow the keyword on its line or come on the next one.
    std::size_t next = 1;
    std::vector<Token> counts(header.tokens.begin() + 1, header.tokens.end());
    const Line* countLine = &header;
    if (counts.empty()) {
        if (lines.size() < 2)
            return problem(header, header.tokens[0], "OFF file ends before its vertex and face counts");
        countLine = &lines[1];
        counts = lines[1].tokens;
        next = 2;
    }
    if (counts.size() < 2 || counts.size() > 3)
        return problem(*countLine, counts.empty() ? countLine->tokens[0] : counts[0],
                       "expected the counts \"vertices faces [edges]\"");
    std::int64_t n[3] = {0, 0, 0};
    for (std::size_t i = 0; i < counts.size(); ++i) {
        const std::optional<std::int64_t> v = integer(counts[i].text);
        if (!v || *v < 0) return problem(*countLine, counts[i], quoted(counts[i].text) + " is not a count");
        n[i] = *v;
    }
    const std::int64_t vertices = n[0], faces = n[1];
    const std::size_t available = lines.size() - next;
    if (static_cast<std::uint64_t>(vertices) + static_cast<std::uint64_t>(faces) > available) {
        const Line& last = lines.back();
        return problem(last, last.tokens[0],
                       "the header promises " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                           " faces, the file has " + std::to_string(available) + " lines of data");
    }
    for (std::int64_t v = 0; v < vertices; ++v) {
        const Line& l = lines[next++];
        const std::size_t got = l.tokens.size();
        // Colours (COFF) are 3 or 4 extra values.
        const bool ok = got == vertexNumbers || (colors && (got == vertexNumbers + 3 || got == vertexNumbers + 4));
        if (!ok)
            return problem(l, l.tokens[0],
                           "vertex " + std::to_string(v) + " has " + std::to_string(got) + " numbers, expected " +
                               std::to_string(vertexNumbers) + (colors ? " (+3 or 4 colour values)" : ""));
        for (const Token& t : l.tokens)
            if (!isNumber(t.text)) return problem(l, t, quoted(t.text) + " is not a number");
    }
    for (std::int64_t f = 0; f < faces; ++f) {
        const Line& l = lines[next++];
        const std::optional<std::int64_t> k = integer(l.tokens[0].text);
        if (!k || *k < 3)
            return problem(l, l.tokens[0],
                           "face " + std::to_string(f) + " must start with its vertex count (3 or more)");
        const std::size_t extra = l.tokens.size() - 1 - std::min<std::size_t>(l.tokens.size() - 1, *k);
        if (l.tokens.size() - 1 < static_cast<std::size_t>(*k))
            return problem(l, l.tokens[0],
                           "face " + std::to_string(f) + " announces " + std::to_string(*k) + " vertices but lists " +
                               std::to_string(l.tokens.size() - 1));
        // After the indices a face may carry a colour: 3 or 4 values.
        if (extra != 0 && extra != 3 && extra != 4)
            return problem(l, l.tokens[*k + 1],
                           "face " + std::to_string(f) + " has " + std::to_string(extra) + " values after its " +
                               std::to_string(*k) + " vertex indices");
        for (std::int64_t i = 1; i <= *k; ++i) {
            const Token& t = l.tokens[i];
            const std::optional<std::int64_t> idx = integer(t.text);
            if (!idx || *idx < 0 || *idx >= vertices)
                return problem(l, t,
                               "face " + std::to_string(f) + " uses vertex " + quoted(t.text) +
                                   " but the vertices are numbered 0 to " + std::to_string(vertices - 1));
        }
        for (std::size_t i = *k + 1; i < l.tokens.size(); ++i)
            if (!isNumber(l.tokens[i].text))
                return problem(l, l.tokens[i], quoted(l.tokens[i].text) + " is not a number");
    }
    if (next < lines.size())
        return problem(lines[next], lines[next].tokens[0],
                       "data after the last of the " + std::to_string(faces) + " faces the header announces");
    return std::nullopt;
}

std::optional<MeshTextProblem> checkPlyHeader(std::string_view text, std::string* ignoredLines) {
    int lineNumber = 0;
    std::size_t start = 0;
    bool ascii = false;
    // Element lines of an ASCII body, one per element, as the header announces them.
    std::uint64_t announcedLines = 0;
    std::string announced;  // "vertex 437645, face 871414"
    // A line without a keyword, not yet known to be harmless. Assimp skips
    // such a line, and it does no harm outside an element's properties (a
    // Blender 2.47 exporter wrote one before the first element); among
    // them it ends the property list early, and the body is then misread.
    int unknownLine = 0;
    std::string unknownKeyword;
    int ignoredCount = 0;
    std::string firstIgnored;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(start, end - start);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        ++lineNumber;
        const std::size_t wordEnd = line.find_first_of(" \t");
        const std::string_view keyword = line.substr(0, wordEnd);
        const auto at = [&](int number, std::string message) { return MeshTextProblem{number, 1, std::move(message)}; };
        const auto unknown = [&](int number, std::string_view word) {
            return at(number, "unknown PLY header line " + quoted(word) +
                                  " (expected comment, obj_info, element, property or end_header)");
        };
        if (lineNumber == 1) {
            if (line != "ply") return at(lineNumber, "a PLY file starts with a line \"ply\"");
        } else if (lineNumber == 2) {
            const bool known = line.starts_with("format ascii ") || line.starts_with("format binary_little_endian ") ||
                               line.starts_with("format binary_big_endian ");
            if (!known) return at(lineNumber, "expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
            ascii = line.starts_with("format ascii ");
        } else if (keyword == "end_header") {
            if (ascii) {
                std::uint64_t bodyLines = 0;
                for (std::size_t p = end + 1; p < text.size() && bodyLines < announcedLines;) {
                    const std::size_t next = std::min(text.find('\n', p), text.size());
                    if (text.substr(p, next - p).find_first_not_of(" \t\r") != std::string_view::npos) ++bodyLines;
                    p = next + 1;
                }
                // Assimp reads a truncated ASCII body without a word, making
                // up the missing elements (faces of vertex 0).
                if (bodyLines < announcedLines)
                    return at(lineNumber, "the header announces " + std::to_string(announcedLines) +
                                              " lines of data (" + announced + "), the file has " +
                                              std::to_string(bodyLines));
            }
            if (ignoredLines && ignoredCount > 0)
                *ignoredLines = ignoredCount == 1 ? "ignored PLY header line " + firstIgnored
                                                  : "ignored " + std::to_string(ignoredCount) +
                                                        " PLY header lines, the first line " + firstIgnored;
            return std::nullopt;
        } else if (keyword == "element") {
            // "element <name> <count>"
            std::vector<std::string_view> words;
            for (std::size_t p = 0; p < line.size();) {
                const std::size_t b = line.find_first_not_of(" \t", p);
                if (b == std::string_view::npos) break;
                const std::size_t e = std::min(line.find_first_of(" \t", b), line.size());
                words.push_back(line.substr(b, e - b));
                p = e;
            }
            const std::optional<std::int64_t> count = words.size() == 3 ? integer(words[2]) : std::nullopt;
            if (!count || *count < 0) return at(lineNumber, "expected \"element <name> <count>\"");
            announcedLines += static_cast<std::uint64_t>(*count);
            announced += (announced.empty() ? "" : ", ") + std::string(words[1]) + " " + std::to_string(*count);
            unknownLine = 0;  // it came before this element's properties: harmless
        } else if (keyword == "property") {
            if (unknownLine > 0) return unknown(unknownLine, unknownKeyword);
        } else if (keyword != "comment" && keyword != "obj_info") {
            if (unknownLine == 0) {
                unknownLine = lineNumber;
                unknownKeyword = std::string(keyword);
            }
            if (ignoredCount++ == 0)
                firstIgnored = std::to_string(lineNumber) + " without a keyword (" + quotedLine(line) + ")";
        }
        start = end + 1;
    }
    return MeshTextProblem{lineNumber, 1, "the PLY header has no end_header line"};
}

namespace {
std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}
}  // namespace

bool strictlyCheckedText(const std::filesystem::path& path) {
    const std::string ext = lowerExtension(path);
    return ext == ".obj" || ext == ".off" || ext == ".ply";
}

std::optional<MeshTextProblem> checkMeshText(const std::filesystem::path& path, std::string_view text,
                                             std::string* accepted) {
    const std::string ext = lowerExtension(path);
    if (ext == ".obj") return checkObjText(text);
    if (ext == ".off") return checkOffText(text);
    if (ext == ".ply") return checkPlyHeader(text, accepted);
    return std::nullopt;
}

}  // namespace raycache
