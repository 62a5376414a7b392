#include "bench/BenchmarkRecord.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>
#include <vector>

#include "bench/ResultsJson.h"
#include "core/Errors.h"
#include "core/LaneLevels.h"
#include "core/SampleSummary.h"

namespace raycache {

namespace {

constexpr std::string_view kDirtySuffix = "-dirty";

// Writing a probe file beside the target is the only sure test that the
// JSON can be written there once the run is over.
void checkWritableJsonPath(const std::filesystem::path& path) {
    const std::string what = "--json " + path.string() + ": ";
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw InputError(what + "that is a directory, not a file");
    const std::filesystem::path parent = path.parent_path().empty() ? "." : path.parent_path();
    if (!std::filesystem::is_directory(parent, ec))
        throw InputError(what + "'" + parent.string() + "' " +
                         (std::filesystem::exists(parent, ec) ? "is not a directory" : "does not exist"));
    const std::filesystem::path probe =
        parent / ("." + path.filename().string() + ".probe-" + std::to_string(static_cast<long>(::getpid())));
    const bool writable = static_cast<bool>(std::ofstream(probe));
    std::filesystem::remove(probe, ec);
    if (!writable) throw InputError(what + "cannot write to the directory '" + parent.string() + "'");
}

bool safeInShell(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           std::string_view("_@%+=:,./-").find(c) != std::string_view::npos;
}

}  // namespace

BenchmarkRecord::BenchmarkRecord(std::string benchmark, int argc, const char* const* argv,
                                 std::filesystem::path jsonPath, int workerThreads)
    : benchmark_(std::move(benchmark)),
      command_(shellCommandLine(argc, argv)),
      path_(std::move(jsonPath)),
      environment_(currentRunEnvironment(workerThreads)),
      cpuAtStart_(currentCpuSample()) {
    if (!path_.empty()) checkWritableJsonPath(path_);
}

std::optional<BenchmarkRecord> BenchmarkRecord::open(std::string benchmark, int argc, const char* const* argv,
                                                     std::filesystem::path jsonPath, int workerThreads) {
    try {
        return BenchmarkRecord(std::move(benchmark), argc, argv, std::move(jsonPath), workerThreads);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return std::nullopt;
    }
}

int BenchmarkRecord::write(const nlohmann::json& settings, const nlohmann::json& figures) const {
    if (path_.empty()) return 0;
    const std::string& commit = environment_.build.gitCommit;
    const bool dirty = commit.size() > kDirtySuffix.size() && commit.ends_with(kDirtySuffix);
    const char* requested = std::getenv("RAYCACHE_LANES");
    const double others = othersCpuShare(cpuAtStart_, currentCpuSample());
    nlohmann::json document = {
        {"benchmark", benchmark_},
        {"command", command_},
        {"environment", toJson(environment_)},
        {"lane_level", laneLevelName(laneLevel())},
        {"lanes_requested", requested ? nlohmann::json(requested) : nlohmann::json()},
        {"git_commit", dirty ? commit.substr(0, commit.size() - kDirtySuffix.size()) : commit},
        {"dirty", dirty},
        {"others_cpu_share", others >= 0.0 ? nlohmann::json(others) : nlohmann::json()},
        {"load_average_after", currentLoadAverage().toString()},
        {"settings", settings},
    };
    document.update(figures);
    try {
        writeJsonFile(path_, document);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}

std::string shellCommandLine(int argc, const char* const* argv) {
    std::string line;
    for (int i = 0; i < argc; ++i) {
        const std::string_view arg(argv[i]);
        if (i > 0) line += ' ';
        bool safe = !arg.empty();
        for (char c : arg) safe = safe && safeInShell(c);
        if (safe) {
            line += arg;
            continue;
        }
        line += '\'';
        for (char c : arg) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
        line += '\'';
    }
    return line;
}

nlohmann::json benchmarkVariantJson(VariantTimes times, int framesPerRun) {
    for (double& ms : times.milliseconds) ms /= framesPerRun;
    for (double& ms : times.warmupMilliseconds) ms /= framesPerRun;
    times.work /= static_cast<std::uint64_t>(framesPerRun);
    nlohmann::json json = toJson(times);
    json["name"] = times.name;
    const double median = times.median();
    json["rays"] = times.work;
    json["mrays_per_s"] = finiteOrNull(static_cast<double>(times.work) / (median * 1e3));
    return json;
}

nlohmann::json summaryJson(std::span<const double> samples, const std::string& unit) {
    const SampleSummary s = summarize(samples);
    return {{"samples_" + unit, std::vector<double>(samples.begin(), samples.end())},
            {"median_" + unit, s.median}, {"min_" + unit, s.min}, {"max_" + unit, s.max}};
}

}  // namespace raycache
