#include "bench/Experiment.h"

namespace raycache {

std::string toString(BenchSize size) {
    switch (size) {
        case BenchSize::Tiny:
            return "tiny";
        case BenchSize::Quick:
            return "quick";
        case BenchSize::Full:
            return "full";
    }
    return "unknown";
}

std::string experimentMarkdown(const ExperimentOutput& output) {
    std::string s = "# " + output.title + "\n\n";
    for (const std::string& c : output.caveats) s += "> **Note:** " + c + "\n\n";
    s += output.markdown + "\n";
    if (!output.plots.empty()) {
        s += "## Plots\n\n";
        for (const std::string& p : output.plots) s += "![" + p + "](" + p + ")\n\n";
    }
    if (!output.images.empty()) {
        s += "## Images\n\n";
        for (const std::string& i : output.images) s += "- [" + i + "](" + i + ")\n";
        s += "\n";
    }
    s += "Every frame time and metric: [results.json](results.json).\n";
    return s;
}

}  // namespace raycache
