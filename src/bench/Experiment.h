#pragma once
// One of the documents' experiments, reproduced: it renders, measures,
// and writes results/<name>/ — results.json (settings, environment, every
// frame time, every metric), results.md (the documents' figures beside ours),
// SVG plots and images — and returns what the report needs.
#include <filesystem>
#include <string>
#include <vector>

#include "core/ProgressBar.h"
#include "bench/RunEnvironment.h"
#include "cache/CachePolicy.h"
#include "core/Parallel.h"

namespace raycache {

// How big a run is. Full: the documents' resolutions and frame counts.
// Quick: lower resolution and fewer frames, all experiments in minutes.
// Tiny: seconds, for tests; its numbers mean nothing.
enum class BenchSize { Tiny, Quick, Full };

std::string toString(BenchSize size);

struct BenchSettings {
    BenchSize size = BenchSize::Quick;
    int threads = 0;  // 0 = all hardware threads
    std::filesystem::path outDir = "results";
    // `bench --cache-policy`: what the experiments that honour it
    // (Experiment::honoursCachePolicy) give their cached renders. Always by
    // default, so the reported numbers stay comparable from run to run.
    CachePolicyMode cachePolicy = CachePolicyMode::Always;
};

// What an experiment is given to run with.
struct ExperimentContext {
    BenchSettings settings;
    const Parallel& parallel;
    ProgressBar& progress;
    RunEnvironment environment;
    std::filesystem::path dir;  // results/<name>/, created before run()
};

// What an experiment wrote and found, for the terminal and the report.
struct ExperimentOutput {
    std::string name;
    std::string title;
    std::string markdown;                // the body of results.md (also placed in the report)
    std::vector<std::string> plots;      // SVG files, relative to the experiment's dir
    std::vector<std::string> images;     // PNG files, relative to the experiment's dir
    std::vector<std::string> headlines;  // one-line findings, printed at the end
    std::vector<std::string> caveats;    // what is not comparable or not available, said plainly
};

class Experiment {
public:
    virtual ~Experiment() = default;
    virtual std::string name() const = 0;   // e.g. "table-5.1"
    virtual std::string title() const = 0;  // e.g. "Table 5.1: hybrid pipeline ± CCT on behind-N"
    // Work for the progress bar's estimate, in the unit run() advances it by
    // (megapixels rendered, weighted by a rough cost per pixel).
    virtual double estimatedWork(const BenchSettings& settings) const = 0;
    // Runs the experiment, writing its files into context.dir.
    virtual ExperimentOutput run(ExperimentContext& context) const = 0;
    // Whether its cached renders take BenchSettings::cachePolicy. The
    // documents' tables and figures of what a cube holds (Table 5.x, fill
    // rate, quality) keep `always`: their protocol caches every frame.
    virtual bool honoursCachePolicy() const { return false; }
};

// The experiment's results.md: title, `body`, caveats, and links to plots and images.
std::string experimentMarkdown(const ExperimentOutput& output);

}  // namespace raycache
