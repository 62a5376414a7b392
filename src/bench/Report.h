#pragma once
// results/report.md: every experiment's findings in one page, readable on
// its own — what was run, on what, how big, the documents' figures beside
// ours, the caveats, and links to every table, plot and image.
#include <string>
#include <vector>

#include "bench/Experiment.h"
#include "bench/RunEnvironment.h"

namespace raycache {

struct ReportInput {
    BenchSettings settings;
    RunEnvironment environment;
    double wallSeconds = 0.0;
    std::string command;           // how it was run, e.g. "raycache bench all --quick"
    std::string loadAverageAfter;  // /proc/loadavg's figures when the last experiment ended
    double othersCpuShare = -1.0;  // othersCpuShare() over the whole run; negative = unknown
    std::string busyWarning;       // busyMachineWarning() for the whole run, empty when quiet
    std::string processes;         // an MPI job: which process ran which experiment; empty for one process
    std::vector<ExperimentOutput> experiments;
};

// The Markdown text; links are relative to the results directory.
std::string reportMarkdown(const ReportInput& input);

}  // namespace raycache
