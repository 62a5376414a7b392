// A benchmark program's command line: options bound to variables, --help,
// and one error line for a bad option. The parser (CLI11, header-only) is
// compiled once, in BenchmarkOptions.cpp, rather than in every benchmark
// program: at -O3 its header costs more compile time than a benchmark's own
// code (docs/testing.md: where the time goes).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace raycache {

class BenchmarkOptions {
public:
    // Inclusive bounds an integer option must lie in.
    struct Range {
        int min;
        int max;
    };

    explicit BenchmarkOptions(const std::string& description);
    ~BenchmarkOptions();
    BenchmarkOptions(const BenchmarkOptions&) = delete;
    BenchmarkOptions& operator=(const BenchmarkOptions&) = delete;

    // `--name VALUE` sets `value`; --help shows the value it starts with as the default.
    void add(const std::string& name, int& value, const std::string& help, std::optional<Range> range = {});
    void add(const std::string& name, float& value, const std::string& help);
    void add(const std::string& name, std::string& value, const std::string& help);
    // Comma-separated or repeated values replace the starting list.
    void add(const std::string& name, std::vector<std::string>& values, const std::string& help);
    // Left empty unless given.
    void add(const std::string& name, std::optional<int>& value, const std::string& help,
             std::optional<Range> range = {});
    // `--name` sets `value` to true; a name written "!--name" sets it to false.
    void flag(const std::string& name, bool& value, const std::string& help);
    // --threads: worker threads, 0 = all.
    void addThreads(int& threads);
    // --json FILE: the run's record (bench/BenchmarkRecord.h); empty unless given.
    void addJson(std::filesystem::path& path);

    // Reads the command line. Returns the exit code when the program should
    // stop here (after --help, or after printing why an option is wrong), and
    // nothing when it should run.
    std::optional<int> parse(int argc, char** argv);

private:
    std::unique_ptr<CLI::App> app_;
};

}  // namespace raycache
