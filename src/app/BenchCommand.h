#pragma once
// `raycache bench <experiment>...|all`: reproduce the documents' experiments
// and write results/<experiment>/ (results.json, results.md, SVG plots,
// images); `all` also writes results/report.md.
#include <iosfwd>
#include <string>
#include <vector>

namespace raycache {

struct BenchCommandOptions {
    std::vector<std::string> experiments;  // names or "all"
    bool quick = false;                    // the default size
    bool full = false;
    bool tiny = false;
    int threads = 0;
    std::string outDir = "results";
    bool list = false;  // print the experiments and exit
    // Progress bar on a terminal, plain lines otherwise; tests force plain lines.
    bool interactive = false;
};

// Runs the experiments, printing progress and findings to `out`. Throws
// InputError for unknown experiments or conflicting options (before running
// anything) and RuntimeError when rendering or writing results fails.
void runBenchCommand(const BenchCommandOptions& options, std::ostream& out);

}  // namespace raycache
