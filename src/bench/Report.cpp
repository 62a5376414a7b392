#include "bench/Report.h"

#include "bench/MachineLoad.h"
#include "bench/MarkdownTable.h"
#include "core/ProgressBar.h"

namespace raycache {

namespace {

std::string sizeDescription(BenchSize size) {
    switch (size) {
        case BenchSize::Full:
            return "**Size: full** — the documents' resolutions (1024×1024; 1920×1080 for Table 5.3) and frame counts.";
        case BenchSize::Quick:
            return "**Size: quick** — lower resolution and fewer frames than the documents (512×512 instead of "
                   "1024×1024 for the speed tables and quality, 960×540 instead of 1920×1080 for Table 5.3, fewer "
                   "warm-up and timed frames, one moving-camera run per variant, 30 Render Cache frames per path at "
                   "512×512 only); the fill-rate experiment keeps the documents' 1024×1024. Ratios are indicative; "
                   "run `raycache bench all --full` for the documents' sizes.";
        case BenchSize::Tiny:
            return "**Size: tiny** — a smoke test at a few dozen pixels; the numbers mean nothing.";
    }
    return "";
}

}  // namespace

std::string reportMarkdown(const ReportInput& in) {
    const RunEnvironment& e = in.environment;
    std::string s = "# raycache: the documents' experiments reproduced\n\n";
    s += "Produced by `" + in.command + "` in " + ProgressBar::formatDuration(in.wallSeconds) + ". " +
         sizeDescription(in.settings.size) + "\n\n";
    s += "The documents (Ruff, SIBGRAPI 2013 and MSc thesis, UFF 2013) measured on a GPU with OptiX; raycache "
         "runs on the CPU with Embree. Absolute frame rates are therefore not comparable: the tables place the "
         "documents' figures beside ours, and the comparison that means something is the ratio (speed-up over "
         "uncached ray tracing in the same program on the same machine, frames timed interleaved in one run) "
         "and the image error against the uncached render.\n\n";
    s += "## Machine and build\n\n";
    MarkdownTable env({"", ""});
    env.addRow({"CPU", e.cpuModel + " (" + std::to_string(e.hardwareThreads) + " hardware threads, " +
                           std::to_string(e.workerThreads) + " used)"});
    env.addRow({"OS", e.os});
    env.addRow({"build", e.build.buildType + ", " + e.build.compiler + "; lanes " + e.build.lanes});
    env.addRow({"raycache", e.build.raycacheVersion + ", commit " + e.build.gitCommit});
    env.addRow({"libraries", "Embree " + e.build.embreeVersion + ", oneTBB " + e.build.tbbVersion + ", Assimp " +
                                 e.build.assimpVersion + ", OpenEXR " + e.build.openExrVersion});
    env.addRow({"started", e.startedAt + ", load average " + e.loadAverage + " (1, 5, 15 min) on " +
                               std::to_string(e.hardwareThreads) + " hardware threads"});
    if (!in.loadAverageAfter.empty())
        env.addRow({"finished", "load average " + in.loadAverageAfter + " (1, 5, 15 min); other processes used " +
                                    formatOthersShare(in.othersCpuShare) + " of the CPU time during the run"});
    if (!in.processes.empty()) env.addRow({"processes", in.processes});
    s += env.toMarkdown() + "\n";
    if (!in.busyWarning.empty()) s += "**" + in.busyWarning + ".**\n\n";

    s += "## Findings at a glance\n\n";
    for (const ExperimentOutput& x : in.experiments)
        for (const std::string& h : x.headlines) s += "- " + h + "\n";
    s += "\n";
    bool anyCaveat = false;
    for (const ExperimentOutput& x : in.experiments) anyCaveat = anyCaveat || !x.caveats.empty();
    if (anyCaveat) {
        s += "## Not comparable or not available in this build\n\n";
        for (const ExperimentOutput& x : in.experiments)
            for (const std::string& c : x.caveats) s += "- **" + x.name + "**: " + c + "\n";
        s += "\n";
    }

    for (const ExperimentOutput& x : in.experiments) {
        s += "## " + x.title + "\n\n";
        for (const std::string& c : x.caveats) s += "> **Note:** " + c + "\n\n";
        // The experiment's own links are relative to its directory.
        std::string body = x.markdown;
        for (std::size_t pos = 0; (pos = body.find("](", pos)) != std::string::npos; pos += 2) {
            const std::size_t start = pos + 2;
            if (body.compare(start, 4, "http") != 0 && body.compare(start, 1, "/") != 0)
                body.insert(start, x.name + "/");
        }
        s += body + "\n";
        for (const std::string& p : x.plots) s += "![" + x.name + " " + p + "](" + x.name + "/" + p + ")\n\n";
        s += "Details: [" + x.name + "/results.md](" + x.name + "/results.md), every frame time and metric in [" +
             x.name + "/results.json](" + x.name + "/results.json)";
        if (!x.images.empty()) s += ", " + std::to_string(x.images.size()) + " images in `" + x.name + "/`";
        s += ".\n\n";
    }
    return s;
}

}  // namespace raycache
