// Table 5.3: CCT, uncached and CDCT at the documents' four step/epsilon pairs
// on the two 32-sphere walls at 1920x1080.
#include "bench/TimingTableExperiment.h"

namespace raycache {

namespace {

CdctParameters cdct(float step, float epsilon) {
    return {step, epsilon, 100.0f};
}

// The variants of Table 5.3: the thesis' CDCT (`cdct-parity`) at its four
// step/epsilon pairs, and the improved CDCT (`cdct`, which steps by texels).
std::vector<TimingVariant> table53Variants() {
    return {
        {"standard", "uncached", CacheTechnique::None},
        {"cct", "CCT", CacheTechnique::Cct},
        {"cdct-2/0.2", "CDCT parity 2/0.2", CacheTechnique::CdctParity, cdct(2.0f, 0.2f), "", 2.0},
        {"cdct-0.4/0.05", "CDCT parity 0.4/0.05", CacheTechnique::CdctParity, cdct(0.4f, 0.05f), "", 2.0},
        {"cdct-0.2/0.02", "CDCT parity 0.2/0.02", CacheTechnique::CdctParity, cdct(0.2f, 0.02f), "", 2.0},
        {"cdct-0.02/0.002", "CDCT parity 0.02/0.002", CacheTechnique::CdctParity, cdct(0.02f, 0.002f), "", 2.5},
        {"cdct-improved", "improved CDCT", CacheTechnique::Cdct, cdct(0.4f, 0.05f), "", 2.0},
    };
}

}  // namespace

std::unique_ptr<Experiment> makeTable53Experiment() {
    TimingTableSpec spec;
    spec.name = "table-5.3";
    spec.title = "Table 5.3: CCT, uncached and CDCT on 32 spheres at 1920x1080 (diffuse-32, reflective-32)";
    spec.description =
        "Diffuse: a wall of 32 spheres of which one is a caching mirror. Reflective: all 32 are caching mirrors. "
        "Every variant's frames are timed interleaved; CDCT step/epsilon as in the documents, depths up to 100.";
    spec.rowHeader = "scene";
    spec.scenes = {{"diffuse-32", "Diffuse"}, {"reflective-32", "Reflective"}};
    spec.variants = table53Variants();
    spec.documents = paperTable53();
    spec.rowsAreScenes = false;
    spec.full = {.width = 1920,
                 .height = 1080,
                 .warmupFrames = 2,
                 .timedFrames = 5,
                 .maxTimedFrames = 40,
                 .timeCapSeconds = 60.0};
    // Quick: the time cap keeps `bench all --quick` within 3 minutes on 2 cores.
    spec.quick = {
        .width = 960, .height = 540, .warmupFrames = 1, .timedFrames = 4, .maxTimedFrames = 30, .timeCapSeconds = 5.0};
    spec.tiny = {.width = 48, .height = 27, .warmupFrames = 1, .timedFrames = 1, .cacheResolution = 32};
    return std::make_unique<TimingTableExperiment>(std::move(spec));
}

}  // namespace raycache
