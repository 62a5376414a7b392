#pragma once
// The standalone benchmarks (benchmarks/core_speed, cct_speed) print Markdown
// tables; with --json FILE each also writes every figure of them as one JSON
// document, so the docs can quote them from committed runs
// (docs/bench-runs/, scripts/doc-figures.py) as they quote the bench's
// results.json. This is what every such document holds besides its figures,
// recorded as `raycache bench` records it: the command line, the machine and
// the build (bench/RunEnvironment.h), the lane level in use, the commit and
// whether the build had uncommitted changes, and how busy the machine was.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/InterleavedRuns.h"
#include "bench/MachineLoad.h"
#include "bench/RunEnvironment.h"

namespace raycache {

class BenchmarkRecord {
public:
    // `jsonPath` empty: nothing is written. Otherwise it is checked now,
    // before anything is measured, so a bad path costs no benchmark run:
    // InputError when it names a directory, or its directory is missing or
    // cannot be written to. `workerThreads` as the benchmark runs them.
    BenchmarkRecord(std::string benchmark, int argc, const char* const* argv, std::filesystem::path jsonPath,
                    int workerThreads);

    // Writes {"benchmark", "command", "environment", "lane_level",
    // "lanes_requested", "git_commit", "dirty", "others_cpu_share",
    // "load_average_after", "settings", "scenes"} to the path atomically:
    // readers see the whole document or none. Nothing without a path.
    // Throws RuntimeError when the file cannot be written.
    void write(const nlohmann::json& settings, const nlohmann::json& scenes) const;

private:
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
nlohmann::json benchmarkVariantJson(const VariantTimes& times);

}  // namespace raycache
