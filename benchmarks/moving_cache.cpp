// Caching while the camera moves, from empty caches: uncached against CCT
// with single-resolution cubes, CCT with multi-resolution cubes
// (RayCacheSettings::cubeLevels) and, on request, cubes sized from the view
// (resolutionFromView) and filled from visible surfaces (visibleFill), side by
// side along each scene's own path.
//  - quality (untimed pass): per frame, the hit rate and the PSNR of each
//    cached image against the uncached image of the same camera;
//  - speed: the whole path per run, the variants interleaved, caches emptied
//    before every run; median (min-max) ms per frame.
// With --json FILE it also writes every figure of its tables, with the run's
// settings, machine and build, as one JSON document (bench/BenchmarkRecord.h;
// the docs quote the runs in docs/bench-runs/moving_cache/).
// Usage: moving_cache [--size 1024] [--frames 10] [--rounds 3] [--levels 6] [--scenes grid-32,behind-32]
//                     [--no-multi-res] [--view] [--fill] [--view-fill] [--json FILE]
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "BenchmarkOptions.h"
#include "bench/BenchmarkRecord.h"
#include "bench/InterleavedRuns.h"
#include "bench/ResultsJson.h"
#include "core/Parallel.h"
#include "metrics/ImageMetrics.h"
#include "render/FrameRenderer.h"
#include "scene/BuiltinScenes.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

struct Options {
    int size = 1024, frames = 10, rounds = 3, threads = 0, maxDepth = 5, levels = 6;
    float levelError = 0.25f;
    std::vector<std::string> scenes{"grid-32", "behind-32"};
    bool multiRes = true, view = false, fill = false, viewFill = false;
};

RenderSettings settingsFor(const Options& o, CacheTechnique technique, int levels) {
    RenderSettings s;
    s.maxDepth = o.maxDepth;
    s.width = s.height = o.size;
    s.threads = o.threads;
    s.cache.techniqueOverride = technique;
    s.cache.cubeLevels = levels;
    s.cache.levelErrorBound = o.levelError;
    return s;
}

struct Setup {
    std::string key;  // its name in the JSON
    std::string name;
    RenderSettings settings;
};

std::vector<Setup> variantsFor(const Options& o) {
    std::vector<Setup> variants{{"uncached", "uncached", settingsFor(o, CacheTechnique::None, 1)},
                                {"cct", "CCT", settingsFor(o, CacheTechnique::Cct, 1)}};
    if (o.multiRes)
        variants.push_back({"cct_multi_res", "CCT multi-res", settingsFor(o, CacheTechnique::Cct, o.levels)});
    const auto cct = [&](bool view, bool fill) {
        RenderSettings s = settingsFor(o, CacheTechnique::Cct, 1);
        s.cache.resolutionFromView = view;
        s.cache.visibleFill = fill ? VisibleFill::Exact : VisibleFill::Off;
        return s;
    };
    if (o.view) variants.push_back({"cct_from_view", "CCT from view", cct(true, false)});
    if (o.fill) variants.push_back({"cct_fill", "CCT + fill", cct(false, true)});
    if (o.viewFill) variants.push_back({"cct_from_view_fill", "CCT from view + fill", cct(true, true)});
    return variants;
}

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options{"Caching along a moving camera from empty caches: uncached, CCT, multi-resolution CCT"};
    Options o;
    options.add("--size", o.size, "Image width and height");
    options.add("--frames", o.frames, "Frames of each scene's camera path");
    options.add("--rounds", o.rounds, "Timed runs of the whole path per variant");
    options.addThreads(o.threads);
    options.add("--max-depth", o.maxDepth, "Longest ray path");
    options.add("--levels", o.levels, "Resolution levels of the multi-resolution cubes");
    options.add("--level-error", o.levelError, "RayCacheSettings::levelErrorBound");
    options.add("--scenes", o.scenes, "Built-in scenes");
    options.flag("!--no-multi-res", o.multiRes, "Leave out the multi-resolution cubes");
    options.flag("--view", o.view, "Add CCT with cubes sized from the view (--cache-res-from-view)");
    options.flag("--fill", o.fill, "Add CCT filled from visible surfaces (--cache-fill exact)");
    options.flag("--view-fill", o.viewFill, "Add CCT sized from the view and filled from visible surfaces");
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;
    const Parallel parallel(o.threads);
    const std::optional<BenchmarkRecord> record =
        BenchmarkRecord::open("moving_cache", argc, argv, jsonPath, parallel.threadCount());
    if (!record) return 2;
    nlohmann::json sceneRecords = nlohmann::json::array();

    for (const std::string& name : o.scenes) {
        const auto scene = makeBuiltinScene(name);
        if (!scene) {
            std::fprintf(stderr, "error: unknown scene %s\n", name.c_str());
            return 2;
        }
        const TraceScene tracer(*scene);
        const std::vector<Setup> variants = variantsFor(o);
        std::vector<std::unique_ptr<RayCache>> caches;
        std::vector<std::unique_ptr<FrameRenderer>> renderers;
        for (const Setup& v : variants) {
            caches.push_back(std::make_unique<RayCache>(*scene, v.settings.cache));
            renderers.push_back(
                std::make_unique<FrameRenderer>(*scene, tracer, v.settings, parallel, caches.back().get()));
        }
        const auto camera = [&](int f) { return scene->cameraPath.cameraAt(scene->camera, f); };

        // Quality, untimed: every variant renders the path from empty caches.
        std::printf("## %s, %d², %d frames of its path from empty caches (multi-res: %d levels, error bound %g)\n\n",
                    name.c_str(), o.size, o.frames, o.levels, static_cast<double>(o.levelError));
        std::printf("| frame");
        for (std::size_t v = 1; v < variants.size(); ++v)
            std::printf(" | %s: hits, PSNR dB, MiB", variants[v].name.c_str());
        std::printf(" |\n| ---");
        for (std::size_t v = 1; v < variants.size(); ++v) std::printf(" | ---");
        std::printf(" |\n");
        for (auto& cache : caches) cache->clear();
        std::vector<double> psnrSum(variants.size(), 0.0);
        nlohmann::json records = nlohmann::json::object();
        for (const Setup& v : variants) records[v.key] = {{"name", v.name}};
        for (int f = 0; f < o.frames; ++f) {
            Image truth;
            renderers[0]->render(camera(f), truth);
            std::printf("| %d", f + 1);
            for (std::size_t v = 1; v < variants.size(); ++v) {
                Image image;
                const FrameStats stats = renderers[v]->render(camera(f), image);
                const FrameCacheStats& c = *stats.cache;
                const double db = psnr(image, truth);
                if (f > 0) psnrSum[v] += db;  // frame 1 traces everything: identical, infinite PSNR
                const double hitPercent =
                    c.lookups() ? 100.0 * static_cast<double>(c.hits()) / static_cast<double>(c.lookups()) : 0.0;
                const double mib = static_cast<double>(caches[v]->bytes()) / (1024.0 * 1024.0);
                std::printf(" | %.1f %%, %.2f, %.0f", hitPercent, db, mib);
                records[variants[v].key]["frames"].push_back(
                    {{"hit_percent", hitPercent}, {"psnr_db", finiteOrNull(db)}, {"cache_mib", mib}});
            }
            std::printf(" |\n");
            std::fflush(stdout);
        }
        const double reused = std::max(1, o.frames - 1);
        std::printf("\nMean PSNR against uncached over frames 2-%d (frame 1 is the uncached image):", o.frames);
        for (std::size_t v = 1; v < variants.size(); ++v) {
            std::printf("%s %s %.2f dB", v > 1 ? "," : "", variants[v].name.c_str(), psnrSum[v] / reused);
            records[variants[v].key]["mean_psnr_db"] = finiteOrNull(psnrSum[v] / reused);
        }
        std::printf("\n\n");
        sceneRecords.push_back({{"scene", name}, {"variants", records}});

        // Speed: the whole path per run, interleaved (--rounds 0: quality only).
        if (o.rounds <= 0) continue;
        std::vector<raycache::Variant> timed;
        for (std::size_t v = 0; v < variants.size(); ++v)
            timed.push_back({variants[v].name,
                             [&, v] {
                                 std::uint64_t rays = 0;
                                 Image image;
                                 for (int f = 0; f < o.frames; ++f)
                                     rays += renderers[v]->render(camera(f), image).rays.total();
                                 return rays;
                             },
                             [&, v] { caches[v]->clear(); }});
        const auto times = runInterleaved(timed, 0, o.rounds);
        const double frames = static_cast<double>(o.frames);
        std::printf("| variant | ms per frame, median (min-max) over %d runs | speed-up over uncached |\n", o.rounds);
        std::printf("| --- | --- | --- |\n");
        for (std::size_t v = 0; v < times.size(); ++v) {
            const VariantTimes& t = times[v];
            std::printf("| %s | %.1f (%.1f-%.1f) | %.2fx |\n", t.name.c_str(), t.median() / frames, t.min() / frames,
                        t.max() / frames, times[0].median() / t.median());
            nlohmann::json& variantRecord = sceneRecords.back()["variants"][variants[v].key];
            variantRecord["timing"] = benchmarkVariantJson(t, o.frames);
            variantRecord["speedup"] = times[0].median() / t.median();
        }
        std::printf("\n");
        std::fflush(stdout);
    }
    return record->write({{"size", o.size},
                          {"frames", o.frames},
                          {"rounds", o.rounds},
                          {"threads", o.threads},
                          {"worker_threads", parallel.threadCount()},
                          {"max_depth", o.maxDepth},
                          {"levels", o.levels},
                          {"level_error", o.levelError},
                          {"scenes", o.scenes},
                          {"multi_res", o.multiRes},
                          {"view", o.view},
                          {"fill", o.fill},
                          {"view_fill", o.viewFill}},
                         {{"scenes", sceneRecords}});
}
