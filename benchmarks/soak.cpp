// Soak: a long orbit with caches on, printing memory as it goes, so a slow leak
// or unbounded growth shows as a rising line. Prints resident and live-heap
// sizes every --every frames and, at the end, the growth over the second half
// (after the cubes have filled); docs/performance.md records a run. The short
// version with a pass/fail bound is tests/render/MemorySoakTest.cpp.
// With --json FILE it also writes every figure it prints, with the run's
// settings, machine and build, as one JSON document (bench/BenchmarkRecord.h;
// the docs quote the runs in docs/bench-runs/soak/).
// Usage: soak [--scene room] [--frames 10000] [--size 64] [--cache-res 512] [--technique cct] [--every 500]
//             [--json FILE]
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "BenchmarkOptions.h"
#include "bench/BenchmarkRecord.h"
#include "core/Parallel.h"
#include "core/ProcessMemory.h"
#include "render/FramePipeline.h"
#include "scene/BuiltinScenes.h"
#include "scene/Material.h"
#include "session/PipelineFactory.h"
#include "session/RenderJob.h"
#include "trace/TraceScene.h"

using namespace raycache;

int main(int argc, char** argv) {
    BenchmarkOptions options{"Memory over a long camera path with caching on"};
    std::string sceneName = "room", technique = "cct";
    int frames = 10000, size = 64, cacheResolution = 512, every = 500, threads = 0;
    options.add("--scene", sceneName, "Built-in scene with an orbiting camera");
    options.add("--frames", frames, "Frames to render");
    options.add("--size", size, "Image width and height");
    options.add("--cache-res", cacheResolution, "Caching-cube face resolution",
                BenchmarkOptions::Range{CacheSettings::kMinFaceResolution, CacheSettings::kMaxFaceResolution});
    options.add("--technique", technique, "cct, cdct or cdct-parity");
    options.add("--every", every, "Print memory every this many frames");
    options.addThreads(threads);
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;

    const auto scene = makeBuiltinScene(sceneName);
    const auto parsedTechnique = parseCacheTechnique(technique);
    if (!scene || !parsedTechnique || frames < 2 || size < 1 || every < 1) {
        std::fprintf(stderr, "error: unknown scene or technique, or a non-positive count\n");
        return 2;
    }
    const Parallel parallel(threads);
    const std::optional<BenchmarkRecord> record =
        BenchmarkRecord::open("soak", argc, argv, jsonPath, parallel.threadCount());
    if (!record) return 2;
    RenderSettings settings;
    settings.width = settings.height = size;
    settings.threads = threads;
    settings.cache.techniqueOverride = *parsedTechnique;
    settings.cache.resolutionOverride = cacheResolution;
    const TraceScene tracer(*scene);
    RayCache cache(*scene, settings.cache);
    const auto pipeline = makeFramePipeline(*scene, tracer, settings, parallel, &cache);

    std::printf("soak: %s, %dx%d, %d frames, %s with %d^2 faces, %d threads\n", sceneName.c_str(), size, size, frames,
                technique.c_str(), cacheResolution, parallel.threadCount());
    std::printf("%8s %14s %14s %10s %12s\n", "frame", "resident KiB", "heap KiB", "hits %", "invalid %");
    std::size_t residentAtHalf = 0, heapAtHalf = 0;
    // Kept in memory reserved now, so that recording them grows no heap the soak measures.
    struct Sample {
        int frame;
        double residentKib, heapKib, hitPercent, invalidPercent;
    };
    std::vector<Sample> samples;
    samples.reserve(static_cast<std::size_t>(frames / every + 2));
    for (int f = 0; f < frames; ++f) {
        Image film;
        const FrameStats stats = pipeline->render(scene->cameraPath.cameraAt(scene->camera, f), film);
        if (f + 1 == frames / 2) {
            residentAtHalf = residentBytes();
            heapAtHalf = heapBytesInUse();
        }
        if ((f + 1) % every == 0 || f == 0 || f + 1 == frames) {
            const double lookups = stats.cache ? static_cast<double>(stats.cache->lookups()) : 0.0;
            const double hits = stats.cache ? static_cast<double>(stats.cache->hits()) : 0.0;
            const double residentKib = static_cast<double>(residentBytes()) / 1024.0;
            const double heapKib = static_cast<double>(heapBytesInUse()) / 1024.0;
            const double hitPercent = lookups > 0 ? 100.0 * hits / lookups : 0.0;
            const double invalidPercent = stats.cache ? stats.cache->invalidPercentBefore() : 0.0;
            std::printf("%8d %14.0f %14.0f %10.1f %12.2f\n", f + 1, residentKib, heapKib, hitPercent, invalidPercent);
            std::fflush(stdout);
            samples.push_back({f + 1, residentKib, heapKib, hitPercent, invalidPercent});
        }
    }
    const auto kib = [](std::size_t from, std::size_t to) {
        return (static_cast<double>(to) - static_cast<double>(from)) / 1024.0;
    };
    const double residentGrowth = kib(residentAtHalf, residentBytes()), heapGrowth = kib(heapAtHalf, heapBytesInUse());
    std::printf("growth from frame %d to %d: resident %+.0f KiB, heap %+.0f KiB\n", frames / 2, frames,
                residentGrowth, heapGrowth);
    nlohmann::json sampleRecords = nlohmann::json::array();
    for (const Sample& s : samples)
        sampleRecords.push_back({{"frame", s.frame},
                                 {"resident_kib", s.residentKib},
                                 {"heap_kib", s.heapKib},
                                 {"hit_percent", s.hitPercent},
                                 {"invalid_percent", s.invalidPercent}});
    return record->write({{"scene", sceneName},
                          {"frames", frames},
                          {"size", size},
                          {"cache_res", cacheResolution},
                          {"technique", technique},
                          {"every", every},
                          {"threads", threads},
                          {"worker_threads", parallel.threadCount()}},
                         {{"samples", sampleRecords},
                          {"second_half",
                           {{"from_frame", frames / 2},
                            {"to_frame", frames},
                            {"resident_growth_kib", residentGrowth},
                            {"heap_growth_kib", heapGrowth}}}});
}
