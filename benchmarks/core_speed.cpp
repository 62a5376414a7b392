// Frame time of the renderer against a plain single-ray Embree Whitted loop
// (trace/BaselineWhitted) on the same scenes, interleaved in one run. The
// plain loop runs twice: on Embree's built-in spheres, and on raycache's own
// acceleration structure (user-geometry spheres), to separate the two effects.
// Usage: core_speed [--size 1024] [--rounds 15] [--scenes grid-32,behind-32,reflective-32]
#include <CLI/CLI.hpp>
#include <cstdio>

#include "bench/InterleavedRuns.h"
#include "core/Parallel.h"
#include "render/FrameRenderer.h"
#include "scene/BuiltinScenes.h"
#include "trace/BaselineWhitted.h"

using namespace raycache;

int main(int argc, char** argv) {
    CLI::App app{"Renderer vs plain Embree Whitted loop, interleaved frame timing"};
    int size = 1024, rounds = 15, warmup = 3, maxDepth = 5, threads = 0;
    std::vector<std::string> scenes{"grid-32", "behind-32", "reflective-32"};
    app.add_option("--size", size, "Image width and height")->capture_default_str();
    app.add_option("--rounds", rounds, "Timed frames per variant")->capture_default_str();
    app.add_option("--warmup", warmup, "Untimed frames per variant first")->capture_default_str();
    app.add_option("--max-depth", maxDepth, "Longest ray path")->capture_default_str();
    app.add_option("--threads", threads, "Worker threads, 0 = all")->capture_default_str();
    app.add_option("--scenes", scenes, "Built-in scenes")->delimiter(',');
    CLI11_PARSE(app, argc, argv);

    const Parallel parallel(threads);
    std::printf("| scene | variant | ms/frame median | min-max | Mrays/s | rays/frame | vs baseline |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
    for (const std::string& name : scenes) {
        const auto scene = makeBuiltinScene(name);
        if (!scene) {
            std::fprintf(stderr, "error: unknown scene %s\n", name.c_str());
            return 2;
        }
        RenderSettings settings;
        settings.width = settings.height = size;
        settings.maxDepth = maxDepth;
        settings.threads = threads;
        settings.cache.techniqueOverride = CacheTechnique::None;  // uncached, like the plain loop
        const TraceScene tracer(*scene);
        const FrameRenderer renderer(*scene, tracer, settings, parallel);
        Image film(size, size), baselineFilm(size, size);
        const BaselineWhitted plainLoop(*scene, nullptr), plainLoopOurBvh(*scene, &tracer);
        const auto results = runInterleaved(
            {{"plain loop, Embree spheres", [&] { return plainLoop.render(parallel, maxDepth, baselineFilm); }},
             {"plain loop, raycache BVH", [&] { return plainLoopOurBvh.render(parallel, maxDepth, baselineFilm); }},
             {"raycache", [&] { return renderer.render(scene->camera, film).rays.total(); }}},
            warmup, rounds);
        for (const VariantTimes& t : results)
            std::printf("| %s | %s | %.1f | %.1f-%.1f | %.1f | %llu | %.2fx |\n", name.c_str(), t.name.c_str(),
                        t.median(), t.min(), t.max(), static_cast<double>(t.work) / (t.median() * 1e3),
                        static_cast<unsigned long long>(t.work), results[0].median() / t.median());
    }
    return 0;
}
