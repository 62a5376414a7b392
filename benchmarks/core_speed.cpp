// Frame time of the renderer against a plain single-ray Embree Whitted loop
// (trace/BaselineWhitted) and against a floor, on the same scenes,
// interleaved in one run:
//  - the plain loop runs twice: on Embree's built-in spheres, and on
//    raycache's own acceleration structure (user-geometry spheres);
//  - "floor": what no renderer of these images can skip, through the same
//    tracer interface: every tile's camera rays as packets, then one shadow
//    ray per hit and light as packets, no shading and no secondary rays;
//  - "ideal": raycache with every caching object's secondary rays answered
//    for free (RayCacheSettings::ideal), the frame no cache can beat.
// Then, per scene, one more ideal frame with stage timing: each stage's CPU
// time per shaded hit beside the floor's (its wall time times the threads,
// per camera hit).
// Scenes are built-in names or scene files, e.g. the built-in real-mesh
// scenes bunny-glass, teapot-mirrors and dragon-hall (docs/builtin-scenes.md)
// or benchmarks/scenes/bunny-mirror.json (the Stanford bunny and a chrome ball).
// With --json FILE it also writes every figure of its table, with the run's
// settings, machine and build, as one JSON document (bench/BenchmarkRecord.h;
// the docs quote the committed runs in docs/bench-runs/core_speed/).
// Usage: core_speed [--size 1024] [--rounds 15] [--scenes grid-32,behind-32,reflective-32,benchmarks/scenes/bunny-mirror.json] [--json FILE]
#include <array>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>

#include "BenchmarkOptions.h"
#include "bench/BenchmarkRecord.h"
#include "bench/InterleavedRuns.h"
#include "core/Parallel.h"
#include "render/CameraRays.h"
#include "scene/BuiltinScenes.h"
#include "scene/SceneLoader.h"
#include "session/RenderSession.h"
#include "session/StatsJson.h"
#include "trace/BaselineWhitted.h"

using namespace raycache;

namespace {

// Camera rays and one shadow ray per hit and light, as packets per tile.
// Returns the rays traced; `cameraHits`, when given, gets the camera rays that hit.
std::uint64_t renderFloor(const Scene& scene, const TraceScene& tracer, const Parallel& parallel, int size,
                          std::uint64_t* cameraHits = nullptr) {
    const CameraRays cameraRays(scene.camera, size, size);
    constexpr int kTile = 16;
    struct Scratch {
        std::vector<Ray> rays, shadowRays;
        std::vector<TraceHit> hits;
        std::vector<unsigned char> occluded;
        std::uint64_t rays_traced = 0, hits_found = 0;
    };
    std::vector<Scratch> scratch(static_cast<std::size_t>(parallel.threadCount()));
    parallel.forEachTile(size, size, kTile, [&](const TileRange& tile, int worker) {
        Scratch& s = scratch[static_cast<std::size_t>(worker)];
        s.rays.clear();
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) s.rays.push_back(cameraRays.ray(x, y));
        s.hits.resize(s.rays.size());
        tracer.intersectCoherent(s.rays, s.hits);
        s.shadowRays.clear();
        for (std::size_t i = 0; i < s.rays.size(); ++i) {
            if (!s.hits[i].hit()) continue;
            ++s.hits_found;
            const Vec3 p = s.rays[i].origin + s.rays[i].direction * (s.hits[i].t * 0.9999f);
            for (const Light& light : scene.lights) {
                if (light.type == LightType::Directional) {
                    s.shadowRays.push_back(Ray{p, -light.direction});
                } else {
                    const Vec3 d = light.position - p;
                    const float distance = length(d);
                    s.shadowRays.push_back(Ray{p, d / distance, 0.0f, distance});
                }
            }
        }
        s.occluded.resize(s.shadowRays.size());
        tracer.occludedCoherent(s.shadowRays, s.occluded);
        s.rays_traced += s.rays.size() + s.shadowRays.size();
    });
    std::uint64_t total = 0, hits = 0;
    for (Scratch& s : scratch) {
        hits += s.hits_found;
        s.hits_found = 0;
        total += s.rays_traced;
        s.rays_traced = 0;
    }
    if (cameraHits) *cameraHits = hits;
    return total;
}

// The variants' names in the JSON, in the order they run.
constexpr std::array<const char*, 5> kVariantKeys = {"plain_loop", "plain_loop_raycache_bvh", "raycache", "ideal",
                                                     "floor"};

// The ideal frame's stages, CPU ns per shaded hit, beside the floor's ns per
// camera hit: printed as a table row, returned as JSON (null without stage times).
nlohmann::json printStages(const std::string& name, RenderSession& idealTimed, const Scene& scene, Image& film,
                           double floorMs, std::uint64_t floorHits, int threads) {
    idealTimed.render(scene.camera, film);  // the first frame also touches the cubes' memory
    const FrameStats stats = idealTimed.render(scene.camera, film);
    if (!stats.stages) return nullptr;
    const StageTimes& s = *stats.stages;
    const double all = s.nsPerHit(s.total() - s.cacheFrameEnd);
    const double floorNs = floorHits == 0 ? 0.0 : floorMs * 1e6 * threads / static_cast<double>(floorHits);
    std::printf("| %s | ideal frame's stages, ns per hit (%llu hits) | first hits %.1f, surfaces %.1f, shadow rays "
                "%.1f, direct %.1f, secondary rays %.1f, lookups %.1f, resolve %.1f, compose %.1f; all %.1f |"
                " floor %.1f ns per camera hit |\n",
                name.c_str(), static_cast<unsigned long long>(s.hitsShaded), s.nsPerHit(s.firstHits),
                s.nsPerHit(s.surfaces), s.nsPerHit(s.shadowRays), s.nsPerHit(s.directShading),
                s.nsPerHit(s.secondaryRays), s.nsPerHit(s.reuseLookups), s.nsPerHit(s.resolve),
                s.nsPerHit(s.compose), all, floorNs);
    const nlohmann::json nsPerHit = {{"first_hits", s.nsPerHit(s.firstHits)},
                                     {"surfaces", s.nsPerHit(s.surfaces)},
                                     {"shadow_rays", s.nsPerHit(s.shadowRays)},
                                     {"direct", s.nsPerHit(s.directShading)},
                                     {"secondary_rays", s.nsPerHit(s.secondaryRays)},
                                     {"lookups", s.nsPerHit(s.reuseLookups)},
                                     {"resolve", s.nsPerHit(s.resolve)},
                                     {"compose", s.nsPerHit(s.compose)},
                                     {"all", all}};
    return {{"hits_shaded", s.hitsShaded},
            {"ns_per_hit", nsPerHit},
            {"floor_ns_per_camera_hit", floorNs},
            {"floor_camera_hits", floorHits},
            {"cpu_ms", stagesJson(s)}};
}

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options{
        "Renderer vs plain Embree Whitted loop and the primary + shadow ray floor, interleaved frame timing"};
    int size = 1024, rounds = 15, warmup = 3, maxDepth = 5, threads = 0;
    std::vector<std::string> scenes{"grid-32", "behind-32", "reflective-32"};
    options.add("--size", size, "Image width and height");
    options.add("--rounds", rounds, "Timed frames per variant");
    options.add("--warmup", warmup, "Untimed frames per variant first");
    options.add("--max-depth", maxDepth, "Longest ray path");
    options.addThreads(threads);
    options.add("--scenes", scenes,
                "Built-in scenes (real meshes too: bunny-glass, teapot-mirrors, dragon-hall) or scene files (.json)");
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;

    const Parallel parallel(threads);
    const std::optional<BenchmarkRecord> record =
        BenchmarkRecord::open("core_speed", argc, argv, jsonPath, parallel.threadCount());
    if (!record) return 2;
    nlohmann::json sceneRecords = nlohmann::json::array();
    std::printf("| scene | variant | ms/frame median | min-max | Mrays/s | rays/frame | vs plain loop |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
    for (const std::string& name : scenes) {
        std::optional<Scene> scene;
        try {
            scene = loadScene(name);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "error: %s\n", e.what());
            return 2;
        }
        for (const std::string& note : scene->notes) std::fprintf(stderr, "note: %s\n", note.c_str());
        RenderSettings settings;
        settings.width = settings.height = size;
        settings.maxDepth = maxDepth;
        settings.threads = threads;
        settings.cache.techniqueOverride = CacheTechnique::None;  // uncached, like the plain loop
        RenderSettings idealSettings = settings;
        idealSettings.cache.techniqueOverride = CacheTechnique::Cct;
        idealSettings.cache.ideal = true;
        const TraceScene tracer(*scene);
        RenderSession renderer(*scene, settings, tracer, parallel);
        RenderSession ideal(*scene, idealSettings, tracer, parallel);
        Image film(size, size), baselineFilm(size, size);
        const BaselineWhitted plainLoop(*scene, nullptr), plainLoopOurBvh(*scene, &tracer);
        const auto results = runInterleaved(
            {{"plain loop, Embree spheres", [&] { return plainLoop.render(parallel, maxDepth, baselineFilm); }},
             {"plain loop, raycache BVH", [&] { return plainLoopOurBvh.render(parallel, maxDepth, baselineFilm); }},
             {"raycache", [&] { return renderer.render(scene->camera, film).rays.total(); }},
             {"raycache ideal frame", [&] { return ideal.render(scene->camera, film).rays.total(); }},
             {"floor: primary + shadow packets", [&] { return renderFloor(*scene, tracer, parallel, size); }}},
            warmup, rounds);
        nlohmann::json variants = nlohmann::json::object();
        for (std::size_t i = 0; i < results.size(); ++i) {
            const VariantTimes& t = results[i];
            std::printf("| %s | %s | %.1f | %.1f-%.1f | %.1f | %llu | %.2fx |\n", name.c_str(), t.name.c_str(),
                        t.median(), t.min(), t.max(), static_cast<double>(t.work) / (t.median() * 1e3),
                        static_cast<unsigned long long>(t.work), results[0].median() / t.median());
            variants[kVariantKeys[i]] = benchmarkVariantJson(t);
            variants[kVariantKeys[i]]["vs_plain_loop"] = results[0].median() / t.median();
        }
        std::printf("| %s | ideal frame / floor | %.2fx | | | | |\n", name.c_str(),
                    results[3].median() / results[4].median());
        RenderSettings stagedSettings = idealSettings;
        stagedSettings.stageTimes = true;
        RenderSession idealStaged(*scene, stagedSettings, tracer, parallel);
        std::uint64_t floorHits = 0;
        renderFloor(*scene, tracer, parallel, size, &floorHits);
        nlohmann::json stages =
            printStages(name, idealStaged, *scene, film, results[4].median(), floorHits, parallel.threadCount());
        std::fflush(stdout);
        sceneRecords.push_back({{"scene", name},
                                {"scene_name", scene->name},
                                {"variants", std::move(variants)},
                                {"ideal_over_floor", results[3].median() / results[4].median()},
                                {"uncached_over_plain_loop", results[2].median() / results[0].median()},
                                {"ideal_frame_stages", std::move(stages)}});
    }
    return record->write({{"size", size},
                          {"rounds", rounds},
                          {"warmup", warmup},
                          {"max_depth", maxDepth},
                          {"threads", threads},
                          {"worker_threads", parallel.threadCount()},
                          {"scenes", scenes},
                          {"variants", kVariantKeys}},
                         {{"scenes", sceneRecords}});
}
