#pragma once
// Error types. InputError: the user's input (file, argument) is wrong; the CLI
// exits 2. RuntimeError: something failed while running (I/O); exit 1.
#include <stdexcept>
#include <string>

namespace raycache {

// Where in an input the offending value is. Every field is optional.
struct InputLocation {
    std::string file;      // path of the file, empty for command-line input
    int line = 0;          // 1-based, 0 = unknown
    int column = 0;        // 1-based, 0 = unknown
    std::string jsonPath;  // JSON pointer such as /objects/3/material/ior
};

class InputError : public std::runtime_error {
public:
    InputError(InputLocation where, const std::string& what)
        : std::runtime_error(format(where, what)), where_(std::move(where)) {}
    explicit InputError(const std::string& what) : InputError(InputLocation{}, what) {}

    const InputLocation& where() const { return where_; }

private:
    // "file:line:col: /json/path: message", omitting unknown parts.
    static std::string format(const InputLocation& w, const std::string& what) {
        std::string s;
        if (!w.file.empty()) {
            s += w.file;
            if (w.line > 0) s += ":" + std::to_string(w.line) + ":" + std::to_string(w.column);
            s += ": ";
        }
        if (!w.jsonPath.empty()) s += w.jsonPath + ": ";
        return s + what;
    }
    InputLocation where_;
};

// A file whose content is wrong where no finer location (line, field) is known.
[[noreturn]] inline void failFile(const std::string& file, const std::string& message) {
    throw InputError(InputLocation{.file = file}, message);
}

class RuntimeError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace raycache
