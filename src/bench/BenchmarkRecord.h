#pragma once
// The standalone benchmarks (benchmarks/*_speed, moving_cache, soak) print
// Markdown tables; with --json FILE each also writes every figure of them as
// one JSON document, so the docs can quote them from committed runs
// (docs/bench-runs/, scripts/doc-figures.py) as they quote the bench's
// results.json. This is what every such document holds besides its figures,
// recorded as `raycache bench` records it: the command line, the machine and
// the build (bench/RunEnvironment.h), the lane level in use, the commit and
// whether the build had uncommitted changes, and how busy the machine was.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>

#include "bench/InterleavedRuns.h"
#include "bench/MachineLoad.h"
#include "bench/RunEnvironment.h"

namespace raycache {

class BenchmarkRecord {
public:
    // The record of this run of `benchmark`; `workerThreads` as it runs them.
    // `jsonPath` empty: a record that writes nothing. Otherwise the path is
    // checked now, before anything is measured, so a bad one costs no run:
    // when it names a directory, or its directory is missing or cannot be
    // written to, one line "error: …" goes to stderr and there is no record
    // (the benchmark exits 2).
    static std::optional<BenchmarkRecord> open(std::string benchmark, int argc, const char* const* argv,
                                               std::filesystem::path jsonPath, int workerThreads);

    // Writes {"benchmark", "command", "environment", "lane_level",
    // "lanes_requested", "git_commit", "dirty", "others_cpu_share",
    // "load_average_after", "settings"} and each member of the object
    // `figures` to the path atomically: readers see the whole document or
    // none. Nothing without a path. Returns the benchmark's exit code: 0, or
    // 1 after one line "error: …" when the file cannot be written.
    int write(const nlohmann::json& settings, const nlohmann::json& figures) const;

private:
    BenchmarkRecord(std::string benchmark, int argc, const char* const* argv, std::filesystem::path jsonPath,
                    int workerThreads);

    std::string benchmark_;
    std::string command_;
    std::filesystem::path path_;
    RunEnvironment environment_;
    CpuSample cpuAtStart_;
};

// The command line as a shell reads it back: an argument holding anything
// but letters, digits and _@%+=:,./- is single-quoted.
std::string shellCommandLine(int argc, const char* const* argv);

// One variant of an interleaved run (bench/ResultsJson.h's timings, every
// frame in ms with median, min and max) with its work: "rays" per frame and
// "mrays_per_s" at the median frame, as the benchmarks' tables print them.
// A run that renders `framesPerRun` frames (a camera path) counts per frame.
nlohmann::json benchmarkVariantJson(VariantTimes times, int framesPerRun = 1);

// Samples of one quantity that are not an interleaved run's frames (a part
// of a frame, a load, a share): {"samples_<unit>", "median_<unit>",
// "min_<unit>", "max_<unit>"}, e.g. "median_ms".
nlohmann::json summaryJson(std::span<const double> samples, const std::string& unit = "ms");

}  // namespace raycache
