#include "BenchmarkOptions.h"

#include <CLI/CLI.hpp>

namespace raycache {

namespace {

void check(CLI::Option* option, const std::optional<BenchmarkOptions::Range>& range) {
    if (range) option->check(CLI::Range(range->min, range->max));
}

}  // namespace

BenchmarkOptions::BenchmarkOptions(const std::string& description) : app_(std::make_unique<CLI::App>(description)) {}

BenchmarkOptions::~BenchmarkOptions() = default;

void BenchmarkOptions::add(const std::string& name, int& value, const std::string& help, std::optional<Range> range) {
    check(app_->add_option(name, value, help)->capture_default_str(), range);
}

void BenchmarkOptions::add(const std::string& name, float& value, const std::string& help) {
    app_->add_option(name, value, help)->capture_default_str();
}

void BenchmarkOptions::add(const std::string& name, std::string& value, const std::string& help) {
    app_->add_option(name, value, help)->capture_default_str();
}

void BenchmarkOptions::add(const std::string& name, std::vector<std::string>& values, const std::string& help) {
    app_->add_option(name, values, help)->delimiter(',')->capture_default_str();
}

void BenchmarkOptions::add(const std::string& name, std::optional<int>& value, const std::string& help,
                           std::optional<Range> range) {
    check(app_->add_option(name, value, help), range);
}

void BenchmarkOptions::flag(const std::string& name, bool& value, const std::string& help) {
    app_->add_flag(name, value, help);
}

void BenchmarkOptions::addThreads(int& threads) {
    add("--threads", threads, "Worker threads, 0 = all", Range{0, 1024});
}

void BenchmarkOptions::addJson(std::filesystem::path& path) {
    app_->add_option("--json", path, "Also write every figure, the settings, machine and build to this JSON file");
}

std::optional<int> BenchmarkOptions::parse(int argc, char** argv) {
    try {
        app_->parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        return app_->exit(error);
    }
    return std::nullopt;
}

}  // namespace raycache
