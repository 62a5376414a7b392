// How long loading a scene takes (issue 39's goal: the 871k-triangle Stanford
// dragon in at most 1.5 s): loadScene() alone, from the file to the Scene the
// renderer takes (mesh reading, checks, repairs, normals), without building
// the ray tracing structures. Wall milliseconds per round, median (min-max).
// With --json FILE it also writes every figure of its table, with the run's
// settings, machine and build, as one JSON document (bench/BenchmarkRecord.h;
// the docs quote the runs in docs/bench-runs/scene_load_speed/).
// Usage: scene_load_speed [--rounds 5] --scenes dragon-hall,scene.json,... [--json FILE]
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "BenchmarkOptions.h"
#include "bench/BenchmarkRecord.h"
#include "core/SampleSummary.h"
#include "scene/SceneLoader.h"

using namespace raycache;

namespace {

std::size_t triangleCount(const Scene& scene) {
    std::size_t triangles = 0;
    for (const SceneObject& object : scene.objects)
        if (const auto* mesh = std::get_if<MeshShape>(&object.shape)) triangles += mesh->mesh->triangles.size();
    return triangles;
}

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options{"Time loading scenes (built-in names or scene files), side by side"};
    int rounds = 5;
    std::vector<std::string> scenes{"dragon-hall"};
    options.add("--rounds", rounds, "Loads per scene, interleaved", BenchmarkOptions::Range{1, 1000});
    options.add("--scenes", scenes, "Built-in scenes or scene files (.json, .gltf, .glb)");
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;
    // Loading runs on one thread.
    const std::optional<BenchmarkRecord> record = BenchmarkRecord::open("scene_load_speed", argc, argv, jsonPath, 1);
    if (!record) return 2;

    std::vector<std::vector<double>> ms(scenes.size());
    std::vector<std::size_t> triangles(scenes.size());
    for (int r = 0; r < rounds; ++r)
        for (std::size_t s = 0; s < scenes.size(); ++s) {
            const auto start = std::chrono::steady_clock::now();
            try {
                const Scene scene = loadScene(scenes[s]);
                if (r == 0)
                    for (const std::string& note : scene.notes) std::fprintf(stderr, "note: %s\n", note.c_str());
                triangles[s] = triangleCount(scene);
            } catch (const std::exception& e) {
                std::fprintf(stderr, "error: %s\n", e.what());
                return 2;
            }
            ms[s].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
    std::printf("| scene | triangles | load ms median | min-max | rounds |\n| --- | --- | --- | --- | --- |\n");
    nlohmann::json records = nlohmann::json::array();
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const SampleSummary sum = summarize(ms[s]);
        std::printf("| %s | %zu | %.1f | %.1f-%.1f | %d |\n", scenes[s].c_str(), triangles[s], sum.median, sum.min,
                    sum.max, rounds);
        records.push_back({{"scene", scenes[s]}, {"triangles", triangles[s]}, {"load", summaryJson(ms[s])}});
    }
    return record->write({{"rounds", rounds}, {"scenes", scenes}}, {{"scenes", records}});
}
