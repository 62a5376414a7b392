// What an animated scene's per-frame update costs and what it does to the
// frame, interleaved in one run: deforming meshes refitted vs rebuilt
// (TraceOptions), and every animated built-in with caches off and on.
// Per variant and frame: the update (pose, tracer, caches) and the render,
// in wall milliseconds; medians with min-max over the frames of all rounds.
// With --json FILE it also writes every figure of its table, with the run's
// settings, machine and build, as one JSON document (bench/BenchmarkRecord.h;
// the docs quote the runs in docs/bench-runs/scene_update_speed/).
// Usage: scene_update_speed [--size 1024] [--frames 24] [--rounds 3] [--json FILE]
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "BenchmarkOptions.h"
#include "bench/BenchmarkRecord.h"
#include "core/Parallel.h"
#include "core/SampleSummary.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct SceneVariant {
    std::string scene;
    std::string label;
    RenderSettings settings;
    std::vector<double> updateMs, renderMs, frameMs;
};

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options{"Per-frame update cost of animated scenes: refit vs rebuild, caches off vs on"};
    int size = 1024, frames = 24, rounds = 3, threads = 0;
    options.add("--size", size, "Image side in pixels");
    options.add("--frames", frames, "Frames per round, from time 0 at the scene's fps");
    options.add("--rounds", rounds, "Rounds; variants interleave within each frame");
    options.addThreads(threads);
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;
    const std::optional<BenchmarkRecord> record =
        BenchmarkRecord::open("scene_update_speed", argc, argv, jsonPath, Parallel(threads).threadCount());
    if (!record) return 2;

    std::vector<SceneVariant> variants;
    const auto add = [&](const std::string& scene, const std::string& label, CacheTechnique technique,
                         DeformingMeshUpdate deforming) {
        SceneVariant v{scene, label, {}, {}, {}, {}};
        v.settings.width = v.settings.height = size;
        v.settings.threads = threads;
        v.settings.cache.techniqueOverride = technique;
        v.settings.trace.deformingMeshes = deforming;
        variants.push_back(std::move(v));
    };
    add("cloth", "refit, uncached", CacheTechnique::None, DeformingMeshUpdate::Refit);
    add("cloth", "rebuild, uncached", CacheTechnique::None, DeformingMeshUpdate::Rebuild);
    for (const char* scene : {"room-moving", "orbit", "cloth", "light-sweep"}) {
        add(scene, "uncached", CacheTechnique::None, DeformingMeshUpdate::Refit);
        add(scene, "CCT", CacheTechnique::Cct, DeformingMeshUpdate::Refit);
    }

    for (int round = 0; round < rounds; ++round) {
        std::vector<Scene> scenes;
        std::vector<std::unique_ptr<RenderSession>> sessions;
        scenes.reserve(variants.size());
        for (SceneVariant& v : variants) {
            scenes.push_back(*makeBuiltinScene(v.scene));
            sessions.push_back(std::make_unique<RenderSession>(scenes.back(), v.settings));
        }
        Image film;
        for (int frame = 0; frame < frames; ++frame) {
            for (std::size_t i = 0; i < variants.size(); ++i) {
                const Scene& scene = scenes[i];
                const auto start = Clock::now();
                sessions[i]->setTime(static_cast<float>(frame) / scene.fps);
                const double update = msSince(start);
                const auto renderStart = Clock::now();
                sessions[i]->render(scene.camera, film);
                // Frame 0 builds the caches' first stores and pays page faults: not a steady frame.
                if (frame == 0) continue;
                variants[i].updateMs.push_back(update);
                variants[i].renderMs.push_back(msSince(renderStart));
                variants[i].frameMs.push_back(msSince(start));
            }
        }
        std::fprintf(stderr, "round %d/%d done\n", round + 1, rounds);
    }

    std::printf("%dx%d, %d frames x %d rounds (frame 0 of each round left out)\n", size, size, frames, rounds);
    std::printf("| scene | variant | update ms | render ms | frame ms | update share of the frame |\n|---|---|---|---|---|---|\n");
    const auto cell = [](const std::vector<double>& v) {
        const SampleSummary s = summarize(v);
        char buffer[96];
        std::snprintf(buffer, sizeof buffer, "%.2f (%.2f–%.2f)", s.median, s.min, s.max);
        return std::string(buffer);
    };
    nlohmann::json records = nlohmann::json::array();
    for (const SceneVariant& v : variants) {
        std::vector<double> share;
        for (std::size_t k = 0; k < v.frameMs.size(); ++k) share.push_back(100.0 * v.updateMs[k] / v.frameMs[k]);
        std::printf("| %s | %s | %s | %s | %s | %s %% |\n", v.scene.c_str(), v.label.c_str(), cell(v.updateMs).c_str(),
                    cell(v.renderMs).c_str(), cell(v.frameMs).c_str(), cell(share).c_str());
        records.push_back({{"scene", v.scene},
                           {"variant", v.label},
                           {"update", summaryJson(v.updateMs)},
                           {"render", summaryJson(v.renderMs)},
                           {"frame", summaryJson(v.frameMs)},
                           {"update_share", summaryJson(share, "percent")}});
    }
    return record->write({{"size", size},
                          {"frames", frames},
                          {"rounds", rounds},
                          {"threads", threads},
                          {"worker_threads", Parallel(threads).threadCount()}},
                         {{"variants", records}});
}
