// CCT against uncached ray tracing on behind-N and grid-N, side by side:
//  (a) still camera, caches filled by the warm-up frames (the documents' protocol),
//      with the "ideal" frame (caching objects trace no secondary rays at all);
//  (b) the scene's moving camera path from empty caches, as they fill.
// With --json FILE it also writes every figure of both tables, with the
// ideal cache's bound (uncached / ideal) and the run's settings, machine and
// build, as one JSON document (bench/BenchmarkRecord.h; the docs quote the
// committed runs in docs/bench-runs/cct_speed/).
// Usage: cct_speed [--size 1024] [--rounds 7] [--path-frames 10] [--path-rounds 3] [--scenes a,b] [--json FILE]
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "BenchmarkOptions.h"
#include "bench/BenchmarkRecord.h"
#include "bench/InterleavedRuns.h"
#include "bench/ResultsJson.h"
#include "core/Parallel.h"
#include "render/FrameRenderer.h"
#include "scene/BuiltinScenes.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

RenderSettings settingsFor(int size, int threads, int maxDepth, std::optional<CacheTechnique> technique, bool ideal) {
    RenderSettings s;
    s.maxDepth = maxDepth;
    s.width = s.height = size;
    s.threads = threads;
    s.cache.techniqueOverride = technique;
    s.cache.ideal = ideal;
    return s;
}

// The thesis' Table 5.2 speed-ups (plain ray tracing, grid of caching spheres).
double documentsGridSpeedup(int n) {
    switch (n) {
    case 1: return 1.02;
    case 2: return 1.07;
    case 4: return 1.15;
    case 8: return 1.32;
    case 16: return 1.95;
    case 32: return 2.68;
    default: return 0.0;
    }
}

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options{"CCT vs uncached ray tracing, interleaved frame timing"};
    int size = 1024, rounds = 7, warmup = 2, pathFrames = 10, pathRounds = 3, threads = 0, maxDepth = 5;
    std::vector<std::string> scenes;
    for (const char* family : {"behind-", "grid-"})
        for (int n : {1, 2, 4, 8, 16, 32}) scenes.push_back(family + std::to_string(n));
    options.add("--size", size, "Image width and height");
    options.add("--rounds", rounds, "Timed still frames per variant");
    options.add("--warmup", warmup, "Untimed still frames per variant first (they fill the caches)");
    options.add("--path-frames", pathFrames, "Frames of the moving camera path");
    options.add("--path-rounds", pathRounds, "Timed runs of the whole path per variant");
    options.addThreads(threads);
    options.add("--max-depth", maxDepth, "Longest ray path");
    options.add("--scenes", scenes, "Built-in scenes");
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;
    const Parallel parallel(threads);
    const std::optional<BenchmarkRecord> record =
        BenchmarkRecord::open("cct_speed", argc, argv, jsonPath, parallel.threadCount());
    if (!record) return 2;
    nlohmann::json sceneRecords = nlohmann::json::array();

    std::printf("## (a) still camera, caches filled\n\n");
    std::printf("| scene | uncached ms | CCT ms | ideal ms | speed-up | documents | CCT / ideal | cache MiB |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    struct PathRow {
        std::string scene;
        VariantTimes uncached, cct, ideal;
        double hitPercentLastFrame;
        double lookupsPerPath, hitsPerPath;  // CCT, summed over the path's frames
    };
    std::vector<PathRow> pathRows;
    for (const std::string& name : scenes) {
        const auto scene = makeBuiltinScene(name);
        if (!scene) {
            std::fprintf(stderr, "error: unknown scene %s\n", name.c_str());
            return 2;
        }
        const TraceScene tracer(*scene);
        const RenderSettings plainSettings = settingsFor(size, threads, maxDepth, CacheTechnique::None, false);
        const RenderSettings cctSettings = settingsFor(size, threads, maxDepth, CacheTechnique::Cct, false);
        const RenderSettings idealSettings = settingsFor(size, threads, maxDepth, CacheTechnique::Cct, true);
        const FrameRenderer plain(*scene, tracer, plainSettings, parallel);
        RayCache cctCache(*scene, cctSettings.cache), idealCache(*scene, idealSettings.cache);
        const FrameRenderer cct(*scene, tracer, cctSettings, parallel, &cctCache);
        const FrameRenderer ideal(*scene, tracer, idealSettings, parallel, &idealCache);
        Image film;
        const auto still = runInterleaved(
            {{"uncached", [&] { return plain.render(scene->camera, film).rays.total(); }},
             {"cct", [&] { return cct.render(scene->camera, film).rays.total(); }},
             {"ideal", [&] { return ideal.render(scene->camera, film).rays.total(); }}},
            warmup, rounds);
        const int n = std::stoi(name.substr(name.find('-') + 1));
        const double documents = name.rfind("grid-", 0) == 0 ? documentsGridSpeedup(n) : 0.0;
        char documentsText[32] = "(hybrid, see 5.1)";
        if (documents > 0) std::snprintf(documentsText, sizeof documentsText, "%.2fx", documents);
        std::printf("| %s | %.1f (%.1f-%.1f) | %.1f (%.1f-%.1f) | %.1f (%.1f-%.1f) | %.2fx | %s | %.2f | %.1f |\n",
                    name.c_str(), still[0].median(), still[0].min(), still[0].max(), still[1].median(), still[1].min(),
                    still[1].max(), still[2].median(), still[2].min(), still[2].max(),
                    still[0].median() / still[1].median(), documentsText, still[1].median() / still[2].median(),
                    static_cast<double>(cctCache.bytes()) / (1024.0 * 1024.0));
        std::fflush(stdout);
        sceneRecords.push_back({{"scene", name},
                                {"still",
                                 {{"uncached", benchmarkVariantJson(still[0])},
                                  {"cct", benchmarkVariantJson(still[1])},
                                  {"ideal", benchmarkVariantJson(still[2])},
                                  {"speedup", still[0].median() / still[1].median()},
                                  {"documents_speedup", documents > 0 ? nlohmann::json(documents) : nlohmann::json()},
                                  {"cct_over_ideal", still[1].median() / still[2].median()},
                                  {"ideal_speedup", still[0].median() / still[2].median()},
                                  {"cache_mib", static_cast<double>(cctCache.bytes()) / (1024.0 * 1024.0)}}}});

        // (b) the moving path from empty caches; each run renders the whole path.
        double hitPercent = 0.0, lookups = 0.0, hits = 0.0;
        const auto pathRun = [&](const FrameRenderer& renderer, bool isCct) {
            std::uint64_t rays = 0;
            if (isCct) lookups = hits = 0.0;
            for (int f = 0; f < pathFrames; ++f) {
                const FrameStats stats = renderer.render(scene->cameraPath.cameraAt(scene->camera, f), film);
                rays += stats.rays.total();
                if (isCct && stats.cache) {
                    lookups += static_cast<double>(stats.cache->lookups());
                    hits += static_cast<double>(stats.cache->hits());
                }
                if (isCct && f + 1 == pathFrames && stats.cache && stats.cache->lookups() > 0)
                    hitPercent = 100.0 * static_cast<double>(stats.cache->hits()) /
                                 static_cast<double>(stats.cache->lookups());
            }
            return rays;
        };
        const auto moving = runInterleaved(
            {{"uncached", [&] { return pathRun(plain, false); }},
             {"cct", [&] { return pathRun(cct, true); }, [&] { cctCache.clear(); }},
             {"ideal", [&] { return pathRun(ideal, false); }, [&] { idealCache.clear(); }}},
            0, pathRounds);
        pathRows.push_back({name, moving[0], moving[1], moving[2], hitPercent, lookups, hits});
    }

    std::printf("\n## (b) moving camera path (%d frames from empty caches), ms per frame\n\n", pathFrames);
    // A miss's cost relative to the plain trace it replaces: the traced ray
    // tree of one leaving ray costs T = (uncached - ideal) / lookups; the CCT
    // path costs uncached - hits * T + misses * (c - 1) * T, so
    // c = 1 + (cct - uncached + hits * T) / (misses * T).
    std::printf("| scene | uncached | CCT | ideal | speed-up | CCT hit rate, last frame | miss / plain trace |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
    for (std::size_t i = 0; i < pathRows.size(); ++i) {
        const PathRow& r = pathRows[i];
        const double f = static_cast<double>(pathFrames);
        const double tree = (r.uncached.median() - r.ideal.median()) / r.lookupsPerPath;
        const double misses = r.lookupsPerPath - r.hitsPerPath;
        const double missCost =
            1.0 + (r.cct.median() - r.uncached.median() + r.hitsPerPath * tree) / (misses * tree);
        std::printf("| %s | %.1f (%.1f-%.1f) | %.1f (%.1f-%.1f) | %.1f (%.1f-%.1f) | %.2fx | %.1f%% | %.2fx |\n",
                    r.scene.c_str(), r.uncached.median() / f, r.uncached.min() / f, r.uncached.max() / f,
                    r.cct.median() / f, r.cct.min() / f, r.cct.max() / f, r.ideal.median() / f, r.ideal.min() / f,
                    r.ideal.max() / f, r.uncached.median() / r.cct.median(), r.hitPercentLastFrame, missCost);
        sceneRecords[i]["path"] = {{"uncached", benchmarkVariantJson(r.uncached, pathFrames)},
                                   {"cct", benchmarkVariantJson(r.cct, pathFrames)},
                                   {"ideal", benchmarkVariantJson(r.ideal, pathFrames)},
                                   {"speedup", r.uncached.median() / r.cct.median()},
                                   {"ideal_speedup", r.uncached.median() / r.ideal.median()},
                                   {"cct_hit_percent_last_frame", r.hitPercentLastFrame},
                                   {"cct_lookups", r.lookupsPerPath},
                                   {"cct_hits", r.hitsPerPath},
                                   {"miss_over_plain_trace", finiteOrNull(missCost)}};
    }
    return record->write({{"size", size},
                          {"rounds", rounds},
                          {"warmup", warmup},
                          {"path_frames", pathFrames},
                          {"path_rounds", pathRounds},
                          {"threads", threads},
                          {"worker_threads", parallel.threadCount()},
                          {"max_depth", maxDepth},
                          {"scenes", scenes}},
                         {{"scenes", sceneRecords}});
}
