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
    spec.full = {.width = 1024,
                 .height = 1024,
                 .warmupFrames = 2,
                 .timedFrames = 7,
                 .movingFrames = 10,
                 .movingRounds = 3,
                 .maxTimedFrames = 60,
                 .timeCapSeconds = 20.0};
    // Quick: the time cap keeps `bench all --quick` within 3 minutes on 2 cores.
    spec.quick = {.width = 512,
                  .height = 512,
                  .warmupFrames = 1,
                  .timedFrames = 4,
                  .movingFrames = 10,
                  .movingRounds = 1,
                  .maxTimedFrames = 40,
                  .timeCapSeconds = 1.5};
    spec.tiny = {.width = 32,
                 .height = 32,
                 .warmupFrames = 1,
                 .timedFrames = 2,
                 .movingFrames = 2,
                 .movingRounds = 1,
                 .scenes = 2,
                 .cacheResolution = 32};
    return std::make_unique<TimingTableExperiment>(std::move(spec));
}

}  // namespace raycache
