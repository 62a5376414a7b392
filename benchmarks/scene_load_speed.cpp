// How long loading a scene takes (issue 39's goal: the 871k-triangle Stanford
// dragon in at most 1.5 s): loadScene() alone, from the file to the Scene the
// renderer takes (mesh reading, checks, repairs, normals), without building
// the ray tracing structures. Wall milliseconds per round, median (min-max).
// Usage: scene_load_speed [--rounds 5] --scenes dragon-hall,scene.json,...
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/SampleSummary.h"
#include "scene/SceneLoader.h"

using namespace raycache;

int main(int argc, char** argv) {
    CLI::App app{"Time loading scenes (built-in names or scene files), side by side"};
    int rounds = 5;
    std::vector<std::string> scenes{"dragon-hall"};
    app.add_option("--rounds", rounds, "Loads per scene, interleaved")->capture_default_str()->check(CLI::Range(1, 1000));
    app.add_option("--scenes", scenes, "Built-in scenes or scene files (.json, .gltf, .glb)")->delimiter(',')->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    std::vector<std::vector<double>> ms(scenes.size());
    for (int r = 0; r < rounds; ++r)
        for (std::size_t s = 0; s < scenes.size(); ++s) {
            const auto start = std::chrono::steady_clock::now();
            try {
                const Scene scene = loadScene(scenes[s]);
                if (r == 0)
                    for (const std::string& note : scene.notes) std::fprintf(stderr, "note: %s\n", note.c_str());
            } catch (const std::exception& e) {
                std::fprintf(stderr, "error: %s\n", e.what());
                return 2;
            }
            ms[s].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
    std::printf("| scene | load ms median | min-max | rounds |\n| --- | --- | --- | --- |\n");
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        const SampleSummary sum = summarize(ms[s]);
        std::printf("| %s | %.1f | %.1f-%.1f | %d |\n", scenes[s].c_str(), sum.median, sum.min, sum.max, rounds);
    }
    return 0;
}
