#pragma once
// Test helper for the CLI tests: run a shell command line as a user would,
// capturing its exit code, stdout and stderr.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace raycache::test {

struct RunResult {
    int exitCode;
    std::string out;
    std::string err;
};

// Runs `command`; its stderr goes through `errFile`, which is left in place.
inline RunResult runShell(const std::string& command, const std::filesystem::path& errFile) {
    RunResult result{};
    FILE* pipe = popen((command + " 2>" + errFile.string()).c_str(), "r");
    std::array<char, 4096> buffer{};
    while (pipe && fgets(buffer.data(), buffer.size(), pipe)) result.out += buffer.data();
    const int status = pipe ? pclose(pipe) : -1;
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(errFile);
    result.err.assign(std::istreambuf_iterator<char>(in), {});
    return result;
}

inline int lineCount(const std::string& s) {
    int lines = 0;
    for (char c : s) lines += c == '\n';
    return lines;
}

}  // namespace raycache::test
