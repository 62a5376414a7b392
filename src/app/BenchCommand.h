#pragma once
// `raycache bench <experiment>...|all`: reproduce the documents' experiments
// and write results/<experiment>/ (results.json, results.md, SVG plots,
// images); `all` also writes results/report.md.
#include <iosfwd>
#include <string>
#include <vector>

#include "cache/CachePolicy.h"
#include "core/ProcessGroup.h"

namespace raycache {

struct BenchCommandOptions {
    std::vector<std::string> experiments;  // names or "all"
    bool quick = false;                    // the default size
    bool full = false;
    bool tiny = false;
    int threads = 0;
    std::string outDir = "results";
    // The cached renders of the experiments that honour it (dynamic,
    // parallax); the others keep always (BenchSettings::cachePolicy).
    CachePolicyMode cachePolicy = CachePolicyMode::Always;
    bool list = false;  // print the experiments and exit
    // Progress bar on a terminal, plain lines otherwise; tests force plain lines.
    bool interactive = false;
};

// Runs the experiments, printing progress and findings to `out`. Throws
// InputError for unknown experiments or conflicting options (before running
// anything) and RuntimeError when rendering or writing results fails.
//
// In an MPI job (`group` of several processes, docs/cluster.md) the
// experiments are dealt over the processes by their estimated work, each run
// whole on one process (their frames depend on each other through the caches
// and the interleaved timing); process 0 receives the others' results and
// files, prints and writes everything, as one process would.
void runBenchCommand(const BenchCommandOptions& options, std::ostream& out,
                     const ProcessGroup& group = SingleProcessGroup());

}  // namespace raycache
