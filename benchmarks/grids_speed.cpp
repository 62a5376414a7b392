// The grids against Embree on one model, interleaved over many rounds: per
// round the grids' build (camera and light grids), their primary and shadow
// rays, and Embree's fastest (LOW) build and 16-wide packets on the same
// rays. Medians with min-max over the rounds. For comparing variants of the
// grids where `raycache bench grids` (five frames per model, means) is too
// coarse: run two binaries alternately and compare the medians and ranges.
// With --json FILE it also writes every figure it prints, with the run's
// settings, machine and build, as one JSON document (bench/BenchmarkRecord.h;
// the docs quote the runs in docs/bench-runs/grids_speed/).
// Usage: grids_speed [--model "torus 100k" | cloth | orbit | ...] [--size 1024] [--rounds 15] [--json FILE]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "BenchmarkOptions.h"
#include "bench/BenchmarkRecord.h"
#include "bench/GridsWorkload.h"
#include "core/Elapsed.h"
#include "core/Errors.h"
#include "core/SampleSummary.h"
#include "scene/BuiltinScenes.h"

using namespace raycache;

namespace {

using Clock = std::chrono::steady_clock;

// "torus <thousands>k" or a built-in scene's name (posed as at time 0, kept still).
std::optional<GridsModel> modelNamed(const std::string& name) {
    int thousands = 0;
    char k = 0;
    if (std::sscanf(name.c_str(), "torus %d%c", &thousands, &k) == 2 && k == 'k' && thousands > 0 && thousands <= 4000)
        return gridsTorusModel(thousands * 1000);
    std::optional<Scene> scene = makeBuiltinScene(name);
    if (!scene) return std::nullopt;
    scene->animation = SceneAnimation{};
    return GridsModel{name, std::move(*scene), false};
}

// Prints one part's line and returns its JSON.
nlohmann::json report(const char* label, const std::vector<double>& samples) {
    const SampleSummary s = summarize(samples);
    std::printf("  %-16s %8.2f ms  (%.2f-%.2f)\n", label, s.median, s.min, s.max);
    return summaryJson(samples);
}

double median(const std::vector<double>& samples) { return summarize(samples).median; }

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options{"Grids vs Embree rebuilt, one model, many interleaved rounds (medians with min-max)"};
    std::string modelName = "torus 100k";
    int size = 1024, rounds = 15, threads = 0;
    options.add("--model", modelName, "\"torus <N>k\" (N thousand triangles, 1-4000) or a built-in scene");
    options.add("--size", size, "Image side in pixels", BenchmarkOptions::Range{16, 8192});
    options.add("--rounds", rounds, "Rounds, each timing every part once", BenchmarkOptions::Range{1, 10000});
    options.addThreads(threads);
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;

    const std::optional<GridsModel> model = modelNamed(modelName);
    if (!model) {
        std::fprintf(stderr, "grids_speed: --model: no model named \"%s\"\n", modelName.c_str());
        return 2;
    }
    const Parallel parallel(threads);
    const std::optional<BenchmarkRecord> record =
        BenchmarkRecord::open("grids_speed", argc, argv, jsonPath, parallel.threadCount());
    if (!record) return 2;
    const Scene& scene = model->scene;
    const Camera& camera = scene.camera;
    GridsFrameRays rays = cameraRaysByTile(camera, size);
    {
        // The shadow rays of Embree's hits, as in `bench grids`.
        const TraceScene embree(scene);
        std::vector<std::vector<TraceHit>> hits;
        tracePrimary(embree, rays, parallel, false, &hits);
        addShadowRays(scene, hits, rays);
    }
    std::size_t shadowCount = 0;
    for (const auto& tile : rays.shadow) shadowCount += tile.size();

    TraceOptions gridOptions;
    gridOptions.accelerator = Accelerator::Grids;
    const TraceScene grids(scene, gridOptions);  // its Embree BVH answers only refused rays: not timed
    TraceOptions lowOptions;
    lowOptions.stillSceneQuality = EmbreeBuildQuality::Low;
    std::vector<double> gridBuild, gridCameraBuild, gridLightBuild, gridPrimary, gridShadow, gridTotal, embreeBuild,
        embreePrimary, embreeShadow, embreeTotal;
    // Embree's opponent is built from the scene without its animation, as in
    // `bench grids`: every object still, every hierarchy built at LOW.
    Scene still = scene;
    still.animation = SceneAnimation{};
    std::optional<TraceScene> embreeKept;
    const auto runGrids = [&] {
        const auto start = Clock::now();
        grids.prepareFrame(scene, camera, size, size, parallel);
        gridBuild.push_back(millisecondsSince(start));
        gridCameraBuild.push_back(grids.frameStats().build.primaryBuildMs);
        gridLightBuild.push_back(grids.frameStats().build.shadowBuildMs);
        gridPrimary.push_back(tracePrimary(grids, rays, parallel, true, nullptr));
        gridShadow.push_back(traceShadows(grids, rays, parallel, true));
        gridTotal.push_back(gridBuild.back() + gridPrimary.back() + gridShadow.back());
    };
    const auto runEmbree = [&] {
        // One Embree scene kept over the rounds, as a renderer keeps it.
        embreeBuild.push_back(rebuildOpponent(embreeKept, still, lowOptions));
        const TraceScene& embree = *embreeKept;
        embreePrimary.push_back(tracePrimary(embree, rays, parallel, false, nullptr));
        embreeShadow.push_back(traceShadows(embree, rays, parallel, false));
        embreeTotal.push_back(embreeBuild.back() + embreePrimary.back() + embreeShadow.back());
    };
    // Which tracer goes first alternates from round to round: a build right
    // after the other tracer's rays measured up to four times slower
    // (Embree LOW at 300k triangles, always second: median 42.6 ms).
    for (int round = 0; round < rounds; ++round) {
        if (round % 2 == 0) {
            runGrids();
            runEmbree();
        } else {
            runEmbree();
            runGrids();
        }
    }
    const FrameTraceStats stats = grids.frameStats();
    std::printf("%s, %dx%d, %zu shadow rays, %d threads, %d rounds; grids refused %llu shadow rays\n",
                model->name.c_str(), size, size, shadowCount, parallel.threadCount(), rounds,
                static_cast<unsigned long long>(stats.shadowRefused));
    std::printf("grids\n");
    const nlohmann::json gridsParts = {{"build", report("build", gridBuild)},
                                       {"camera_grid", report("  camera grid", gridCameraBuild)},
                                       {"light_grids", report("  light grids", gridLightBuild)},
                                       {"primary", report("primary", gridPrimary)},
                                       {"shadow", report("shadow", gridShadow)},
                                       {"total", report("total", gridTotal)}};
    std::printf("Embree LOW, rebuilt\n");
    const nlohmann::json embreeParts = {{"build", report("build", embreeBuild)},
                                        {"primary", report("primary", embreePrimary)},
                                        {"shadow", report("shadow", embreeShadow)},
                                        {"total", report("total", embreeTotal)}};
    // The rays alone: Embree's through the hierarchy it has just built, as through a prebuilt one.
    const double totalRatio = median(gridTotal) / median(embreeTotal);
    const double raysRatio =
        (median(gridPrimary) + median(gridShadow)) / (median(embreePrimary) + median(embreeShadow));
    std::printf("grids / Embree: total %.2fx, rays alone (primary + shadow) %.2fx\n", totalRatio, raysRatio);
    return record->write({{"model", model->name},
                          {"size", size},
                          {"rounds", rounds},
                          {"threads", threads},
                          {"worker_threads", parallel.threadCount()}},
                         {{"shadow_rays", shadowCount},
                          {"shadow_refused", stats.shadowRefused},
                          {"grids", gridsParts},
                          {"embree", embreeParts},
                          {"total_over_embree", totalRatio},
                          {"rays_over_embree", raysRatio}});
}
