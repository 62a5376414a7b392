#include "scene/JsonPositions.h"

#include <algorithm>
#include <iterator>
#include <unordered_set>

#include <nlohmann/json.hpp>

namespace raycache {

namespace {

using nlohmann::json;

// Far beyond any real scene file (which nests ~6 levels, holds short names and
// paths, and at most 100000 objects), low enough that the index stays cheap.
constexpr std::size_t kMaxJsonDepth = 64;
constexpr std::size_t kMaxJsonStringBytes = 64u << 10;
constexpr std::size_t kMaxJsonContainerSize = 1000000;

// Input iterator over the text that publishes how far nlohmann's lexer has
// read. SAX callbacks carry no positions, but each one fires right after the
// lexer consumed its token, so this is the end of that token (numbers: one
// character more, the lexer's lookahead).
class TrackingIterator {
public:
    using iterator_category = std::input_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = const char&;

    TrackingIterator(const char* p, const char** consumed) : p_(p), consumed_(consumed) {}

    reference operator*() const { return *p_; }
    TrackingIterator& operator++() {
        ++p_;
        *consumed_ = p_;
        return *this;
    }
    TrackingIterator operator++(int) {
        TrackingIterator old = *this;
        ++*this;
        return old;
    }
    bool operator==(const TrackingIterator& o) const { return p_ == o.p_; }

private:
    const char* p_;
    const char** consumed_;
};

// The containers being parsed, innermost last.
struct Frame {
    std::string pointer;
    bool isArray = false;
    std::size_t nextIndex = 0;                // arrays: index of the next element
    std::optional<std::string> memberPointer;  // objects: member whose value comes next
    std::unordered_set<std::string> names;     // objects: member names seen so far
};

// SAX handler recording where every value and member name starts.
class PositionRecorder {
public:
    PositionRecorder(std::string_view text, const char** consumed, std::size_t start,
                     std::unordered_map<std::string, std::size_t>& valueOffsets,
                     std::unordered_map<std::string, std::size_t>& keyOffsets)
        : text_(text), consumed_(consumed), mark_(start), valueOffsets_(valueOffsets),
          keyOffsets_(keyOffsets) {}

    bool null() { return value(); }
    bool boolean(bool) { return value(); }
    bool number_integer(json::number_integer_t) { return value(); }
    bool number_unsigned(json::number_unsigned_t) { return value(); }
    bool number_float(json::number_float_t, const json::string_t&) { return value(); }
    bool string(json::string_t& s) {
        if (s.size() > kMaxJsonStringBytes)
            return overLimit("string of " + std::to_string(s.size()) + " bytes, more than the limit of " +
                             std::to_string(kMaxJsonStringBytes));
        return value();
    }
    bool binary(json::binary_t&) { return value(); }

    bool start_object(std::size_t) {
        if (!roomForChild()) return false;
        Frame f;
        f.pointer = recordValue();
        frames_.push_back(std::move(f));
        return true;
    }
    bool key(json::string_t& name) {
        const std::size_t start = tokenStart();
        Frame& f = frames_.back();
        if (name.size() > kMaxJsonStringBytes)
            return overLimit("member name of " + std::to_string(name.size()) + " bytes, more than the limit of " +
                             std::to_string(kMaxJsonStringBytes));
        if (f.names.size() >= kMaxJsonContainerSize)
            return overLimit("object with more than " + std::to_string(kMaxJsonContainerSize) + " members");
        std::string member = appendJsonPointer(f.pointer, name);
        if (!f.names.insert(name).second) {
            // nlohmann would silently keep the last one; a repeated name is
            // almost always a copy-paste mistake, so refuse it.
            duplicate_ = DuplicateName{start, member, name};
            return false;
        }
        keyOffsets_[member] = start;
        f.memberPointer = std::move(member);
        mark_ = consumedOffset();
        return true;
    }
    bool end_object() { return endContainer(); }
    bool start_array(std::size_t) {
        if (!roomForChild()) return false;
        Frame f;
        f.pointer = recordValue();
        f.isArray = true;
        frames_.push_back(std::move(f));
        return true;
    }
    bool end_array() { return endContainer(); }

    bool parse_error(std::size_t position, const std::string& lastToken, const json::exception& ex) {
        JsonSyntaxError e;
        e.pointer = nextValuePointer();
        if (ex.id == 406) {
            // out_of_range.406: a number too large for a double. Point at the number.
            errorOffset_ = tokenStart();
            e.message = "number " + lastToken + " is out of range (it would be infinite)";
        } else {
            // `position` counts the characters read, the offending one included.
            const std::size_t lastRead = std::min(position > 0 ? position - 1 : 0, text_.size());
            e.message = cleanMessage(ex.what());
            // A misplaced token is reported where it starts, not at its last
            // character; a malformed one where it went wrong, except a bad
            // literal ("tru]"), which reads best from its start. tokenStart()
            // may have skipped a misplaced ',' or ':', hence the min.
            const bool wholeToken = e.message.find("- unexpected ") != std::string::npos ||
                                    e.message.find("- invalid literal") != std::string::npos;
            errorOffset_ = wholeToken ? std::min(tokenStart(), lastRead) : lastRead;
        }
        error_ = std::move(e);
        return false;
    }

    struct DuplicateName {
        std::size_t offset;
        std::string pointer;
        std::string name;
    };
    const std::optional<DuplicateName>& duplicate() const { return duplicate_; }
    const std::optional<JsonSyntaxError>& error() const { return error_; }
    std::size_t errorOffset() const { return errorOffset_; }

private:
    bool value() {
        if (!frames_.empty() && frames_.back().isArray && frames_.back().nextIndex >= kMaxJsonContainerSize)
            return overLimit("array with more than " + std::to_string(kMaxJsonContainerSize) + " elements");
        recordValue();
        return true;
    }

    // Checked before a container opens: every open container costs a pointer
    // string as long as its depth, so unbounded nesting would cost quadratic
    // time and memory (a 200 kB file of '[' took 21 s before this limit).
    bool roomForChild() {
        if (frames_.size() >= kMaxJsonDepth)
            return overLimit("nested more than " + std::to_string(kMaxJsonDepth) +
                             " levels deep (arrays and objects inside each other)");
        if (!frames_.empty() && frames_.back().isArray && frames_.back().nextIndex >= kMaxJsonContainerSize)
            return overLimit("array with more than " + std::to_string(kMaxJsonContainerSize) + " elements");
        return true;
    }

    // Stops the parse with an error at the token just read (the value that is too much).
    bool overLimit(std::string message) {
        errorOffset_ = tokenStart();
        error_ = JsonSyntaxError{{}, nextValuePointer(), std::move(message)};
        return false;
    }

    // Records where the value that just ended its token starts; returns its pointer.
    std::string recordValue() {
        const std::size_t start = tokenStart();
        std::string pointer = nextValuePointer();
        if (!frames_.empty()) {
            Frame& f = frames_.back();
            if (f.isArray) ++f.nextIndex;
            else f.memberPointer.reset();
        }
        valueOffsets_[pointer] = start;
        mark_ = consumedOffset();
        return pointer;
    }

    bool endContainer() {
        frames_.pop_back();
        if (!frames_.empty() && !frames_.back().isArray) frames_.back().memberPointer.reset();
        mark_ = consumedOffset();
        return true;
    }

    // Pointer of the value the parser is about to deliver.
    std::string nextValuePointer() const {
        if (frames_.empty()) return "";
        const Frame& f = frames_.back();
        if (f.isArray) return appendJsonPointer(f.pointer, std::to_string(f.nextIndex));
        return f.memberPointer ? *f.memberPointer : f.pointer;
    }

    // The current token starts at the first character after the previous
    // token that is neither whitespace nor a separator the parser consumed
    // without a callback (':' and ',').
    std::size_t tokenStart() const {
        std::size_t i = mark_;
        while (i < text_.size()) {
            const char c = text_[i];
            if (c != ' ' && c != '\t' && c != '\n' && c != '\r' && c != ',' && c != ':') break;
            ++i;
        }
        return i;
    }

    std::size_t consumedOffset() const { return static_cast<std::size_t>(*consumed_ - text_.data()); }

    // "[json.exception.parse_error.101] parse error at line 1, column 5: syntax
    // error ..." -> "syntax error ...": the position is reported our way.
    static std::string cleanMessage(const std::string& what) {
        std::string s = what;
        if (const auto close = s.find("] "); s.rfind("[json.exception.", 0) == 0 && close != std::string::npos)
            s.erase(0, close + 2);
        if (s.rfind("parse error", 0) == 0) {
            if (const auto colon = s.find(": "); colon != std::string::npos) s.erase(0, colon + 2);
        }
        std::replace(s.begin(), s.end(), '\n', ' ');
        return s;
    }

    std::string_view text_;
    const char** consumed_;
    std::size_t mark_;  // end of the previous token
    std::vector<Frame> frames_;
    std::unordered_map<std::string, std::size_t>& valueOffsets_;
    std::unordered_map<std::string, std::size_t>& keyOffsets_;
    std::optional<DuplicateName> duplicate_;
    std::optional<JsonSyntaxError> error_;
    std::size_t errorOffset_ = 0;
};

}  // namespace

JsonPositions::JsonPositions(std::string_view text) : text_(text) {
    // nlohmann skips a UTF-8 byte order mark; so do the offsets and columns.
    const std::size_t start = text_.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
    lineStarts_.push_back(start);
    for (std::size_t i = 0; i < text_.size(); ++i)
        if (text_[i] == '\n') lineStarts_.push_back(i + 1);

    const char* consumed = text_.data();
    PositionRecorder recorder(text_, &consumed, start, valueOffsets_, keyOffsets_);
    const bool ok = json::sax_parse(TrackingIterator(text_.data(), &consumed),
                                    TrackingIterator(text_.data() + text_.size(), &consumed), &recorder);
    if (ok) return;
    if (const auto& dup = recorder.duplicate()) {
        const TextPosition first = keyAt(dup->pointer);
        syntaxError_ = JsonSyntaxError{positionOf(dup->offset), dup->pointer,
                                       "duplicate member name \"" + dup->name + "\" (first at line " +
                                           std::to_string(first.line) + ", column " +
                                           std::to_string(first.column) + ")"};
    } else if (const auto& err = recorder.error()) {
        syntaxError_ = *err;
        syntaxError_->position = positionOf(recorder.errorOffset());
    } else {
        syntaxError_ = JsonSyntaxError{positionOf(static_cast<std::size_t>(consumed - text_.data())), "", "invalid JSON"};
    }
}

TextPosition JsonPositions::valueAt(const std::string& pointer) const {
    const auto it = valueOffsets_.find(pointer);
    return it == valueOffsets_.end() ? TextPosition{} : positionOf(it->second);
}

TextPosition JsonPositions::keyAt(const std::string& pointer) const {
    const auto it = keyOffsets_.find(pointer);
    return it == keyOffsets_.end() ? valueAt(pointer) : positionOf(it->second);
}

TextPosition JsonPositions::positionOf(std::size_t offset) const {
    offset = std::clamp(offset, lineStarts_.front(), text_.size());
    const auto after = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
    const std::size_t lineStart = after == lineStarts_.begin() ? 0 : *std::prev(after);
    int column = 1;
    for (std::size_t i = lineStart; i < offset; ++i) {
        // Count code points, not bytes: skip UTF-8 continuation bytes.
        if ((static_cast<unsigned char>(text_[i]) & 0xC0) != 0x80) ++column;
    }
    return {static_cast<int>(after - lineStarts_.begin()), column};
}

std::string appendJsonPointer(const std::string& parent, std::string_view token) {
    std::string s = parent;
    s += '/';
    for (const char c : token) {
        if (c == '~') s += "~0";
        else if (c == '/') s += "~1";
        else s += c;
    }
    return s;
}

}  // namespace raycache
