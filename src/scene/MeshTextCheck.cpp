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

namespace {

// PLY's scalar types: the spec's names and their sized aliases.
struct PlyType {
    std::string_view name;
    int bytes = 0;
    bool integer = false;
    bool isSigned = false;
};

constexpr std::array<PlyType, 16> kPlyTypes = {{{"char", 1, true, true},
                                                {"uchar", 1, true, false},
                                                {"short", 2, true, true},
                                                {"ushort", 2, true, false},
                                                {"int", 4, true, true},
                                                {"uint", 4, true, false},
                                                {"float", 4, false, true},
                                                {"double", 8, false, true},
                                                {"int8", 1, true, true},
                                                {"uint8", 1, true, false},
                                                {"int16", 2, true, true},
                                                {"uint16", 2, true, false},
                                                {"int32", 4, true, true},
                                                {"uint32", 4, true, false},
                                                {"float32", 4, false, true},
                                                {"float64", 8, false, true}}};

const PlyType* plyType(std::string_view name) {
    for (const PlyType& type : kPlyTypes)
        if (type.name == name) return &type;
    return nullptr;
}

struct PlyProperty {
    const PlyType* lengthType = nullptr;  // a list's length; nullptr for a scalar
    const PlyType* type = nullptr;        // the scalar's, or the list items'
    std::string_view name;
    int line = 0;
};

struct PlyElement {
    std::string_view name;
    std::int64_t count = 0;
    int line = 0;
    int column = 0;
    std::vector<PlyProperty> properties;
    // In a "face" element, the lists Assimp reads as the vertex indices and
    // the texture coordinates (the last of each name), else -1.
    int vertexIndices = -1;
    int textureCoordinates = -1;
    int lastList = -1;  // the index of the last list property, else -1

    bool hasList() const { return lastList >= 0; }
    // Bytes of one instance in a binary body with every list empty.
    std::uint64_t leastBinaryBytes() const {
        std::uint64_t bytes = 0;
        for (const PlyProperty& p : properties) bytes += (p.lengthType ? p.lengthType : p.type)->bytes;
        return bytes;
    }
};

// Words separated by blanks, each with its 1-based column.
std::vector<Token> plyWords(std::string_view line) {
    std::vector<Token> words;
    for (std::size_t p = 0; p < line.size();) {
        const std::size_t b = line.find_first_not_of(" \t", p);
        if (b == std::string_view::npos) break;
        const std::size_t e = std::min(line.find_first_of(" \t", b), line.size());
        words.push_back({line.substr(b, e - b), static_cast<int>(b) + 1});
        p = e;
    }
    return words;
}

// A name Assimp and we read the same way: printable ASCII without blanks.
bool plainWord(std::string_view word) {
    return !word.empty() && std::all_of(word.begin(), word.end(), [](char c) { return c > 0x20 && c < 0x7f; });
}

// Where a line (its trailing \r removed) holds a byte other than printable
// text and tabs, else npos. Assimp's line reader ends a line at NUL, \r and
// \f, and then skips to the next \n, past the end of its buffer if there is
// none (the hang and bad free of docs/testing.md findings 17 and 18).
std::size_t firstControlByte(std::string_view line) {
    for (std::size_t i = 0; i < line.size(); ++i) {
        const auto byte = static_cast<unsigned char>(line[i]);
        if ((byte < 0x20 && byte != '\t') || byte == 0x7f) return i;
    }
    return std::string_view::npos;
}

std::string hexByte(unsigned char byte) {
    constexpr std::string_view kDigits = "0123456789abcdef";
    return std::string("0x") + kDigits[byte >> 4] + kDigits[byte & 15];
}

std::string plural(std::uint64_t n, std::string_view word) {
    return std::to_string(n) + " " + std::string(word) + (n == 1 ? "" : "s");
}

// "vertex 437645, face 871414"
std::string announcedElements(const std::vector<PlyElement>& elements) {
    std::string announced;
    for (const PlyElement& e : elements)
        announced += (announced.empty() ? "" : ", ") + std::string(e.name) + " " + std::to_string(e.count);
    return announced;
}

std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) {
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

std::uint64_t saturatingMultiply(std::uint64_t a, std::uint64_t b) {
    return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b;
}

// A list length stored in a binary body, in the file's byte order.
std::int64_t binaryLength(std::string_view bytes, const PlyType& type, bool bigEndian) {
    std::uint64_t value = 0;
    for (int i = 0; i < type.bytes; ++i)
        value = value << 8 |
                static_cast<unsigned char>(bytes[static_cast<std::size_t>(bigEndian ? i : type.bytes - 1 - i)]);
    const int bits = 8 * type.bytes;
    if (type.isSigned && (value >> (bits - 1)) != 0)
        return static_cast<std::int64_t>(value) - (std::int64_t{1} << bits);
    return static_cast<std::int64_t>(value);
}

// Assimp reads a face's texture coordinates through its vertex indices,
// the i-th value through index i / 2, past the indices when there are
// fewer than half as many (and through a null pointer without any), so
// they must come as a pair per vertex (or not at all).
std::optional<std::string> textureCoordinatesNotPerVertex(const PlyElement& face, std::uint64_t index,
                                                          std::int64_t vertexIndices, std::int64_t textureCoordinates) {
    if (face.textureCoordinates < 0 || textureCoordinates == 0 || textureCoordinates == 2 * vertexIndices)
        return std::nullopt;
    return "face " + std::to_string(index) + "'s list " +
           quoted(face.properties[static_cast<std::size_t>(face.textureCoordinates)].name) + " has " +
           plural(static_cast<std::uint64_t>(textureCoordinates), "value") + " for its " +
           std::to_string(vertexIndices) + " vertices (2 per vertex, or none)";
}

// Walks a binary body by the header's elements, reading each list's length
// in the file's byte order, and refuses a body shorter than they announce:
// Assimp reads on past the data, into whatever its 1 MiB buffer holds
// there, and sizes a list by its length before reading it.
// Every instance takes at least a byte (an element without properties and
// a nonzero count is refused before), so the walk ends within as many steps
// as the body has bytes; elements without lists are stepped over at once.
std::optional<MeshTextProblem> checkPlyBinaryBody(std::string_view body, const std::vector<PlyElement>& elements,
                                                  bool bigEndian, int endHeaderLine) {
    const std::uint64_t size = body.size();
    std::uint64_t offset = 0;
    const bool lists = std::any_of(elements.begin(), elements.end(), [](const PlyElement& e) { return e.hasList(); });
    // From `offset` on, `needed` bytes of element `element` do not fit: the
    // message adds the least that its `instancesLeft` and the elements after
    // it announce (list lengths not read count as 0, so with lists, or when
    // the sum passes 2^64 - 1, it is a lower bound).
    const auto tooShort = [&](std::size_t element, std::uint64_t needed, std::uint64_t instancesLeft) {
        std::uint64_t announced = saturatingAdd(offset, needed);
        for (std::size_t e = element; e < elements.size(); ++e)
            announced = saturatingAdd(
                announced,
                saturatingMultiply(e == element ? instancesLeft : static_cast<std::uint64_t>(elements[e].count),
                                   elements[e].leastBinaryBytes()));
        return MeshTextProblem{endHeaderLine, 1,
                               "the header announces " +
                                   std::string(lists || announced == UINT64_MAX ? "at least " : "") +
                                   std::to_string(announced) + " bytes of binary data (" + announcedElements(elements) +
                                   "), the file has " + std::to_string(size)};
    };
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const PlyElement& element = elements[e];
        const auto count = static_cast<std::uint64_t>(element.count);
        if (count == 0) continue;
        const std::uint64_t least = element.leastBinaryBytes();
        if (count > (size - offset) / least) return tooShort(e, 0, count);
        if (!element.hasList()) {
            offset += count * least;
            continue;
        }
        for (std::uint64_t i = 0; i < count; ++i) {
            std::uint64_t restOfInstance = least;  // this instance's least bytes not yet read
            std::int64_t listLengths[2] = {0, 0};  // the face's vertex indices and texture coordinates
            for (std::size_t p = 0; p < element.properties.size(); ++p) {
                const PlyProperty& property = element.properties[p];
                const auto fixedBytes =
                    static_cast<std::uint64_t>((property.lengthType ? property.lengthType : property.type)->bytes);
                if (fixedBytes > size - offset) return tooShort(e, restOfInstance, count - i - 1);
                restOfInstance -= fixedBytes;
                if (!property.lengthType) {
                    offset += fixedBytes;
                    continue;
                }
                const std::int64_t length =
                    binaryLength(body.substr(offset, fixedBytes), *property.lengthType, bigEndian);
                if (length < 0)
                    return MeshTextProblem{property.line, 1,
                                           std::string(element.name) + " " + std::to_string(i) + "'s list " +
                                               quoted(property.name) + " has a negative length (" +
                                               std::to_string(length) + ") at byte " + std::to_string(offset) +
                                               " of the binary data"};
                offset += fixedBytes;
                if (static_cast<int>(p) == element.vertexIndices) listLengths[0] = length;
                if (static_cast<int>(p) == element.textureCoordinates) listLengths[1] = length;
                const std::uint64_t items = saturatingMultiply(static_cast<std::uint64_t>(length),
                                                               static_cast<std::uint64_t>(property.type->bytes));
                if (items > size - offset) return tooShort(e, saturatingAdd(items, restOfInstance), count - i - 1);
                offset += items;
            }
            if (auto problem = textureCoordinatesNotPerVertex(element, i, listLengths[0], listLengths[1]))
                return MeshTextProblem{element.properties[static_cast<std::size_t>(element.textureCoordinates)].line, 1,
                                       *problem + " at byte " + std::to_string(offset) + " of the binary data"};
        }
    }
    // Bytes after the last element are accepted: Assimp never reads them.
    return std::nullopt;
}

// Steps through an ASCII body: one instance per line that is not blank, as
// Assimp reads it. Only the lines of elements with a list are split into
// words: Assimp sizes a list by its length before reading its values (a
// length of 3000000000 allocated 24 GB), so each length must be a count
// the line holds. Elements without lists are only counted. Every line, to
// the end of the file, is free of control bytes: Assimp's line reader runs
// past its buffer after some (as in the header).
std::optional<MeshTextProblem> checkPlyAsciiBody(std::string_view text, std::size_t bodyStart, int endHeaderLine,
                                                 const std::vector<PlyElement>& elements) {
    std::uint64_t announcedLines = 0;
    for (const PlyElement& e : elements)
        announcedLines = saturatingAdd(announcedLines, static_cast<std::uint64_t>(e.count));
    std::uint64_t bodyLines = 0;
    std::size_t element = 0;
    std::uint64_t instance = 0;
    int lineNumber = endHeaderLine;
    for (std::size_t position = bodyStart; position < text.size();) {
        const std::size_t next = std::min(text.find('\n', position), text.size());
        std::string_view line = text.substr(position, next - position);
        position = next + 1;
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (const std::size_t control = firstControlByte(line); control != std::string_view::npos)
            return MeshTextProblem{lineNumber, static_cast<int>(control) + 1,
                                   "control byte " + hexByte(static_cast<unsigned char>(line[control])) +
                                       " in the PLY data (only printable text and tabs belong there)"};
        if (bodyLines == announcedLines || line.find_first_not_of(" \t") == std::string_view::npos) continue;
        ++bodyLines;
        while (instance == static_cast<std::uint64_t>(elements[element].count)) {
            ++element;
            instance = 0;
        }
        const PlyElement& owner = elements[element];
        const std::uint64_t index = instance++;
        if (!owner.hasList()) continue;
        const auto instanceName = [&] { return std::string(owner.name) + " " + std::to_string(index); };
        const std::vector<Token> words = plyWords(line);
        std::size_t word = 0;
        std::int64_t listLengths[2] = {0, 0};  // the face's vertex indices and texture coordinates
        int textureCoordinatesColumn = 1;
        // Up to the last list only: the scalars after it need no look, and a
        // header of many of them must not cost that many steps per line.
        for (std::size_t p = 0; p <= static_cast<std::size_t>(owner.lastList); ++p) {
            const PlyProperty& property = owner.properties[p];
            if (!property.lengthType) {
                ++word;
                continue;
            }
            if (word >= words.size())
                return MeshTextProblem{lineNumber, static_cast<int>(line.size()) + 1,
                                       instanceName() + " ends before the length of its list " + quoted(property.name)};
            const Token& lengthWord = words[word++];
            const std::optional<std::int64_t> length = integer(lengthWord.text);
            if (!length || *length < 0)
                return MeshTextProblem{lineNumber, lengthWord.column,
                                       quoted(lengthWord.text) + " is not a length for " + instanceName() + "'s list " +
                                           quoted(property.name)};
            const std::size_t left = words.size() - word;
            if (static_cast<std::uint64_t>(*length) > left)
                return MeshTextProblem{lineNumber, lengthWord.column,
                                       instanceName() + "'s list " + quoted(property.name) + " announces " +
                                           plural(static_cast<std::uint64_t>(*length), "value") + ", its line has " +
                                           std::to_string(left) + " after the length"};
            word += static_cast<std::size_t>(*length);
            if (static_cast<int>(p) == owner.vertexIndices) listLengths[0] = *length;
            if (static_cast<int>(p) == owner.textureCoordinates) {
                listLengths[1] = *length;
                textureCoordinatesColumn = lengthWord.column;
            }
        }
        if (auto problem = textureCoordinatesNotPerVertex(owner, index, listLengths[0], listLengths[1]))
            return MeshTextProblem{lineNumber, textureCoordinatesColumn, *problem};
    }
    // Assimp reads a truncated ASCII body without a word, making up the
    // missing elements (faces of vertex 0).
    if (bodyLines < announcedLines)
        return MeshTextProblem{endHeaderLine, 1,
                               "the header announces " + std::to_string(announcedLines) + " lines of data (" +
                                   announcedElements(elements) + "), the file has " + std::to_string(bodyLines)};
    return std::nullopt;
}

// Reads a PLY header line by line as Assimp does, keeping what later lines
// and the body's check need; read() gives the first problem, if any.
class PlyHeaderReader {
public:
    PlyHeaderReader(std::string_view text, std::string* ignoredLines) : text_(text), ignoredLines_(ignoredLines) {}

    std::optional<MeshTextProblem> read() {
        std::size_t start = 0;
        while (start < text_.size()) {
            std::size_t end = text_.find('\n', start);
            if (end == std::string_view::npos) end = text_.size();
            HeaderLine line{text_.substr(start, end - start), end, false};
            line.endsWithCarriageReturn = !line.text.empty() && line.text.back() == '\r';
            if (line.endsWithCarriageReturn) line.text.remove_suffix(1);
            ++lineNumber_;
            if (auto problem = readLine(line)) return problem;
            if (finished_) return std::nullopt;
            start = end + 1;
        }
        return at(1, "the PLY header has no end_header line");
    }

private:
    enum class Format { kAscii, kLittleEndian, kBigEndian };

    struct HeaderLine {
        std::string_view text;  // without its line break and carriage return
        std::size_t end = 0;    // where its '\n' is, or the text's size
        bool endsWithCarriageReturn = false;
    };

    MeshTextProblem at(int column, std::string message) const { return {lineNumber_, column, std::move(message)}; }

    std::optional<MeshTextProblem> readLine(const HeaderLine& line) {
        if (lineNumber_ == 1) {
            if (line.text != "ply") return at(1, "a PLY file starts with a line \"ply\"");
            return std::nullopt;
        }
        if (const std::size_t control = firstControlByte(line.text); control != std::string_view::npos)
            return at(static_cast<int>(control) + 1,
                      "control byte " + hexByte(static_cast<unsigned char>(line.text[control])) +
                          " in the PLY header (only printable text and tabs belong there)");
        const std::vector<Token> words = plyWords(line.text);
        const std::string_view keyword = words.empty() ? std::string_view() : words[0].text;
        if (lineNumber_ == 2) return readFormat(words);
        if (keyword == "end_header") return endHeader(line, words);
        if (keyword == "element") return declareElement(words);
        if (keyword == "property") return declareProperty(words);
        if (keyword == "comment" || keyword == "obj_info") {
            if (!elements_.empty())
                noteInterruption(words[0].column, std::string(keyword) + " line among the properties of element " +
                                                      quoted(elements_.back().name) +
                                                      ": Assimp would ignore the properties after it");
            return std::nullopt;
        }
        if (keyword == "format") return at(words[0].column, "a second format line");
        // A line without a keyword: Assimp skips it.
        if (!elements_.empty())
            noteInterruption(1, "unknown PLY header line " + quoted(keyword) +
                                    " (expected comment, obj_info, element, property or end_header)");
        if (ignoredCount_++ == 0)
            firstIgnored_ = std::to_string(lineNumber_) + " without a keyword (" + quotedLine(line.text) + ")";
        return std::nullopt;
    }

    std::optional<MeshTextProblem> readFormat(const std::vector<Token>& words) {
        const bool known = words.size() == 3 && words[0].text == "format" &&
                           (words[1].text == "ascii" || words[1].text == "binary_little_endian" ||
                            words[1].text == "binary_big_endian") &&
                           words[2].text == "1.0";
        if (!known) return at(1, "expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
        format_ = words[1].text == "ascii"                  ? Format::kAscii
                  : words[1].text == "binary_little_endian" ? Format::kLittleEndian
                                                            : Format::kBigEndian;
        return std::nullopt;
    }

    std::optional<MeshTextProblem> endHeader(const HeaderLine& line, const std::vector<Token>& words) {
        if (words.size() > 1) return at(words[1].column, "nothing may follow end_header on its line");
        // Assimp's header reader loops forever on an end_header line
        // that ends the file (docs/testing.md finding 19).
        if (line.end == text_.size())
            return at(words[0].column + 10, "the file ends after end_header, without a line break");
        if (auto problem = elementComplete()) return problem;
        if (auto problem = checkBody(line)) return problem;
        if (ignoredLines_ && ignoredCount_ > 0)
            *ignoredLines_ = ignoredCount_ == 1 ? "ignored PLY header line " + firstIgnored_
                                                : "ignored " + std::to_string(ignoredCount_) +
                                                      " PLY header lines, the first line " + firstIgnored_;
        finished_ = true;
        return std::nullopt;
    }

    std::optional<MeshTextProblem> checkBody(const HeaderLine& endHeaderLine) const {
        const std::size_t bodyStart = std::min(endHeaderLine.end + 1, text_.size());
        if (format_ == Format::kAscii) return checkPlyAsciiBody(text_, bodyStart, lineNumber_, elements_);
        const std::string_view body = text_.substr(bodyStart);
        // Assimp drops a line feed that starts the body, taking it for the
        // rest of a "\r\n" after end_header; behind a lone "\n" it is the
        // first data byte, and everything after it would be read one byte early.
        const bool data = std::any_of(elements_.begin(), elements_.end(), [](const PlyElement& e) { return e.count > 0; });
        if (data && !endHeaderLine.endsWithCarriageReturn && !body.empty() && body.front() == '\n')
            return at(1,
                      "the binary data starts with byte 0x0a, which Assimp drops after an end_header line "
                      "ending in \"\\n\" (end it with \"\\r\\n\")");
        return checkPlyBinaryBody(body, elements_, format_ == Format::kBigEndian, lineNumber_);
    }

    std::optional<MeshTextProblem> declareElement(const std::vector<Token>& words) {
        if (auto problem = elementComplete()) return problem;
        const std::optional<std::int64_t> count = words.size() == 3 ? integer(words[2].text) : std::nullopt;
        if (!count || *count < 0) return at(1, "expected \"element <name> <count>\"");
        const Token& name = words[1];
        if (auto problem = checkElementName(name)) return problem;
        const bool known =
            name.text == "vertex" || name.text == "face" || name.text == "edge" || name.text == "material";
        if (name.text == "vertex" || name.text == "face") {
            // Assimp writes every vertex element into one array sized for
            // the first, and every face element into another (heap overflows).
            int& first = name.text == "vertex" ? vertexElementLine_ : faceElementLine_;
            if (first > 0)
                return at(name.column, "a second " + quoted(name.text) + " element (the first is on line " +
                                           std::to_string(first) + "): Assimp writes both into one array");
            first = lineNumber_;
            // Having read none of an unknown element's instances, Assimp
            // would read their data as this element's.
            if (unknownElement_ >= 0) {
                const PlyElement& unknown = elements_[static_cast<std::size_t>(unknownElement_)];
                return MeshTextProblem{unknown.line, unknown.column,
                                       "Assimp reads no " + quoted(unknown.name) +
                                           " instances (an element it does not know), so they may only come "
                                           "after the vertex and face elements"};
            }
        }
        if (!known && *count > 0 && unknownElement_ < 0) unknownElement_ = static_cast<int>(elements_.size());
        elements_.push_back({name.text, *count, lineNumber_, name.column, {}});
        interruptingLine_ = 0;
        return std::nullopt;
    }

    // The element names Assimp misreads.
    std::optional<MeshTextProblem> checkElementName(const Token& name) const {
        if (!plainWord(name.text))
            return at(name.column, "element name " + quoted(name.text) + " is not a plain ASCII word");
        // Assimp takes this one for a texture file's name and reads no count or properties.
        if (name.text == "TextureFile") return at(name.column, "\"element TextureFile\" is not an element to Assimp");
        // Assimp keeps the last triangle of each strip only.
        if (name.text == "tristrips")
            return at(name.column, "Assimp reads one triangle of each triangle strip: use \"element face\"");
        // Assimp reads the count of an element it does not know from the
        // start of its name (finding 20): 555555555 instances of
        // "555555555face", allocated at once, and 0 of most others.
        const bool known =
            name.text == "vertex" || name.text == "face" || name.text == "edge" || name.text == "material";
        if (!known && std::isdigit(static_cast<unsigned char>(name.text[0])))
            return at(name.column,
                      "element name " + quoted(name.text) + " starts with a digit (Assimp reads it as the count)");
        return std::nullopt;
    }

    std::optional<MeshTextProblem> declareProperty(const std::vector<Token>& words) {
        if (elements_.empty()) return at(words[0].column, "a property before any element");
        if (interruptingLine_ > 0) return MeshTextProblem{interruptingLine_, interruptingColumn_, interruption_};
        const bool list = words.size() > 1 && words[1].text == "list";
        if (words.size() != (list ? 5u : 3u))
            return at(words[0].column,
                      "expected \"property <type> <name>\" or \"property list <length type> <item type> <name>\"");
        PlyProperty property{nullptr, nullptr, words.back().text, lineNumber_};
        const Token& typeWord = words[list ? 3 : 1];
        if (list) {
            property.lengthType = plyType(words[2].text);
            if (!property.lengthType || !property.lengthType->integer)
                return at(words[2].column,
                          quoted(words[2].text) +
                              " is not a list length type (char, uchar, short, ushort, int, uint, int8, uint8, "
                              "int16, uint16, int32 or uint32)");
        }
        property.type = plyType(typeWord.text);
        if (!property.type)
            return at(typeWord.column, "unknown PLY type " + quoted(typeWord.text) +
                                           " (char, uchar, short, ushort, int, uint, float, double, or int8 to float64)");
        if (!plainWord(property.name))
            return at(words.back().column, "property name " + quoted(property.name) + " is not a plain ASCII word");
        PlyElement& element = elements_.back();
        if (list) element.lastList = static_cast<int>(element.properties.size());
        if (element.name == "face" && list) {
            const int index = static_cast<int>(element.properties.size());
            if (property.name == "vertex_indices" || property.name == "vertex_index") element.vertexIndices = index;
            if (property.name == "texcoord") element.textureCoordinates = index;
        }
        element.properties.push_back(property);
        return std::nullopt;
    }

    // Assimp ends an element's property list at any line that is not a
    // property (a comment too), and skips the properties after it, so the
    // body would be misread if one followed. Elsewhere such lines are
    // harmless: the first since the last element line is kept.
    void noteInterruption(int column, std::string message) {
        if (interruptingLine_ != 0) return;
        interruptingLine_ = lineNumber_;
        interruptingColumn_ = column;
        interruption_ = std::move(message);
    }

    // Checks of an element once its properties are known. Its count needs
    // something to count (Assimp loops over empty instances, and allocates
    // one record each for a non-vertex one).
    std::optional<MeshTextProblem> elementComplete() const {
        if (elements_.empty()) return std::nullopt;
        const PlyElement& e = elements_.back();
        if (e.textureCoordinates >= 0 && e.vertexIndices < 0)
            return MeshTextProblem{e.properties[static_cast<std::size_t>(e.textureCoordinates)].line, 1,
                                   "a face's texcoord list needs its vertex_indices list (Assimp reads the one "
                                   "through the other)"};
        if (!e.properties.empty() || e.count == 0) return std::nullopt;
        return MeshTextProblem{e.line, e.column,
                               "element " + quoted(e.name) + " announces " +
                                   plural(static_cast<std::uint64_t>(e.count), "instance") + " but has no properties"};
    }

    std::string_view text_;
    std::string* ignoredLines_;
    int lineNumber_ = 0;
    bool finished_ = false;  // end_header read and the body checked
    Format format_ = Format::kAscii;
    std::vector<PlyElement> elements_;
    int vertexElementLine_ = 0;  // where the vertex element was declared, else 0
    int faceElementLine_ = 0;    // and the face element
    int unknownElement_ = -1;    // the first element Assimp does not know with a nonzero count, else -1
    int interruptingLine_ = 0;   // see noteInterruption
    int interruptingColumn_ = 0;
    std::string interruption_;  // the error if a property follows
    int ignoredCount_ = 0;
    std::string firstIgnored_;
};

}  // namespace

std::optional<MeshTextProblem> checkPlyHeader(std::string_view text, std::string* ignoredLines) {
    return PlyHeaderReader(text, ignoredLines).read();
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
