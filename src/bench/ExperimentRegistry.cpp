#include "bench/ExperimentRegistry.h"

#include <algorithm>

#include "bench/DynamicExperiment.h"
#include "bench/FillRateExperiment.h"
#include "bench/GridsExperiment.h"
#include "bench/ParallaxExperiment.h"
#include "bench/QualityExperiment.h"
#include "bench/RenderCacheExperiment.h"
#include "bench/TimingTableExperiment.h"
#include "bench/WhereCachingPaysExperiment.h"
#include "core/Errors.h"

namespace raycache {

std::vector<std::unique_ptr<Experiment>> allExperiments() {
    std::vector<std::unique_ptr<Experiment>> all;
    all.push_back(makeTable51Experiment());
    all.push_back(makeTable52Experiment());
    all.push_back(makeTable53Experiment());
    all.push_back(makeFillRateExperiment());
    all.push_back(makeQualityExperiment());
    all.push_back(makeParallaxExperiment());
    all.push_back(makeRenderCacheExperiment());
    all.push_back(makeDynamicExperiment());
    all.push_back(makeGridsExperiment());
    all.push_back(makeWhereCachingPaysExperiment());
    return all;
}

std::vector<std::unique_ptr<Experiment>> selectExperiments(const std::vector<std::string>& names) {
    if (names.empty()) throw InputError("name an experiment, or all (see `raycache bench --list`)");
    std::vector<std::string> wanted;
    for (const std::string& n : names) {
        if (n == "all") {
            for (const auto& e : allExperiments()) wanted.push_back(e->name());
            continue;
        }
        wanted.push_back(n);
    }
    std::vector<std::unique_ptr<Experiment>> selected;
    for (const std::string& n : wanted) {
        if (std::any_of(selected.begin(), selected.end(), [&](const auto& e) { return e->name() == n; })) continue;
        auto all = allExperiments();
        auto it = std::find_if(all.begin(), all.end(), [&](const auto& e) { return e->name() == n; });
        if (it == all.end()) {
            std::string known;
            for (const auto& e : all) known += (known.empty() ? "" : ", ") + e->name();
            throw InputError("unknown experiment '" + n + "'; known: " + known + ", all");
        }
        selected.push_back(std::move(*it));
    }
    return selected;
}

}  // namespace raycache
