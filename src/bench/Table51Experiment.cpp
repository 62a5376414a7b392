// Table 5.1: the hybrid pipeline with and without CCT on behind-N.
#include "bench/TimingTableExperiment.h"

namespace raycache {

namespace {

// The documents measured Table 5.1 in their hybrid pipeline: the G-buffer by
// OpenGL when a context can be made (else by primary-ray packets), then the
// deferred ray traced passes.
void selectTable51Pipeline(RenderSettings& settings) {
    settings.pipeline = PipelineKind::Hybrid;
}

// As in the documents, only the main sphere caches; the N spheres behind the
// camera are seen only in its reflection.
void onlyMainSphereCaches(Scene& scene) {
    for (SceneObject& object : scene.objects)
        object.material.cache.technique = object.name == "main" ? CacheTechnique::Cct : CacheTechnique::None;
}

}  // namespace

std::unique_ptr<Experiment> makeTable51Experiment() {
    TimingTableSpec spec;
    spec.name = "table-5.1";
    spec.title = "Table 5.1: hybrid pipeline ± CCT, N reflective spheres behind the camera (behind-N)";
    spec.description =
        "The main mirror sphere faces the camera; N mirror spheres stand behind the camera and are seen only in its "
        "reflection. Only the main sphere caches (CCT). Uncached and CCT frames are timed interleaved.";
    spec.rowHeader = "N";
    for (int n : {0, 1, 2, 4, 8, 16, 32}) spec.scenes.push_back({"behind-" + std::to_string(n), std::to_string(n)});
    spec.variants = {{"standard", "uncached", CacheTechnique::None},
                     {"cct", "CCT", std::nullopt}};  // nullopt: the scene's materials, i.e. only `main` caches
    spec.documents = paperTable51();
    spec.documentsSpeedupColumn = "speedup";
    setSquareTableSizes(spec);
    spec.adjustScene = onlyMainSphereCaches;
    spec.configure = selectTable51Pipeline;
    spec.pipeline = "hybrid";
    return std::make_unique<TimingTableExperiment>(std::move(spec));
}

}  // namespace raycache
