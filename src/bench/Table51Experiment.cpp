// Table 5.1: the hybrid pipeline with and without CCT on behind-N.
#include "bench/TimingTableExperiment.h"

namespace raycache {

namespace {

// ===================== MERGE SWITCH: hybrid pipeline =====================
// This build has no hybrid raster + ray tracing pipeline, so Table 5.1 is
// measured with the ray pipeline and says so. After the hybrid pipeline is
// merged: set kHybridPipelineAvailable to true and select it in
// selectTable51Pipeline (e.g. `settings.pipeline = Pipeline::Hybrid;`).
constexpr bool kHybridPipelineAvailable = false;
void selectTable51Pipeline(RenderSettings& settings) {
    static_cast<void>(settings);
}
// ==========================================================================

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
    spec.full = {1024, 1024, 2, 7, 10, 3, 0};
    spec.quick = {512, 512, 1, 5, 10, 1, 0};
    spec.tiny = {32, 32, 1, 2, 2, 1, 2, 32};
    spec.adjustScene = onlyMainSphereCaches;
    spec.configure = selectTable51Pipeline;
    spec.pipeline = kHybridPipelineAvailable ? "hybrid" : "ray";
    if (!kHybridPipelineAvailable)
        spec.caveats.push_back(
            "hybrid pipeline not available in this build: measured with the ray pipeline, not "
            "comparable to Table 5.1");
    return std::make_unique<TimingTableExperiment>(std::move(spec));
}

}  // namespace raycache
