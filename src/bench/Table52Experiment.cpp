// Table 5.2: plain ray tracing with and without CCT on grid-N.
#include "bench/TimingTableExperiment.h"

namespace raycache {

std::unique_ptr<Experiment> makeTable52Experiment() {
    TimingTableSpec spec;
    spec.name = "table-5.2";
    spec.title = "Table 5.2: plain ray tracing ± CCT, a wall of N caching spheres (grid-N)";
    spec.description =
        "A wall of N mirror spheres faces the camera; every sphere caches (CCT). Uncached and CCT frames are timed "
        "interleaved.";
    spec.rowHeader = "N";
    for (int n : {1, 2, 4, 8, 16, 32}) spec.scenes.push_back({"grid-" + std::to_string(n), std::to_string(n)});
    spec.variants = {{"standard", "uncached", CacheTechnique::None}, {"cct", "CCT", CacheTechnique::Cct}};
    spec.documents = paperTable52();
    spec.documentsSpeedupColumn = "speedup";
    setSquareTableSizes(spec);
    return std::make_unique<TimingTableExperiment>(std::move(spec));
}

}  // namespace raycache
