// The hybrid raster + ray tracing pipeline (SPEC §4), side by side:
//  (a) the G-buffer alone: OpenGL (raster + readback) vs primary-ray packets;
//  (b) whole frames, uncached: ray pipeline vs hybrid (OpenGL) vs hybrid (packets);
//  (c) the documents' Table 5.1 in the hybrid pipeline: behind-N with a still
//      camera, caches filled by the warm-up frames; no cache vs CCT on the main
//      sphere only (the documents' set-up) vs CCT on every mirror.
// With --json FILE it also writes every figure of the tables it prints, with
// the run's settings, machine and build, as one JSON document
// (bench/BenchmarkRecord.h; the docs quote the runs in docs/bench-runs/hybrid_speed/).
// Usage: hybrid_speed [--size 1024] [--rounds 7] [--warmup 2] [--threads 0] [--scenes a,b] [--parts abc] [--json FILE]
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "BenchmarkOptions.h"
#include "bench/BenchmarkRecord.h"
#include "bench/InterleavedRuns.h"
#include "core/Parallel.h"
#include "core/SampleSummary.h"
#include "raster/GBufferRasterizer.h"
#include "render/FramePipeline.h"
#include "render/PacketGBuffer.h"
#include "scene/BuiltinScenes.h"
#include "session/PipelineFactory.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

RenderSettings settingsFor(int size, int threads, PipelineKind pipeline, GBufferSource source) {
    RenderSettings s;
    s.width = s.height = size;
    s.threads = threads;
    s.pipeline = pipeline;
    s.gbuffer = source;
    s.cache.techniqueOverride = CacheTechnique::None;
    return s;
}

std::string range(const VariantTimes& t) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f (%.1f–%.1f)", t.median(), t.min(), t.max());
    return buf;
}

std::string range(const std::vector<double>& samples) {
    const SampleSummary s = summarize(samples);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.1f (%.1f–%.1f)", s.median, s.min, s.max);
    return buf;
}

double documentsBehindSpeedup(int n) {
    switch (n) {
    case 0: return 1.84;
    case 1: return 1.90;
    case 2: return 1.98;
    case 4: return 2.00;
    case 8: return 2.24;
    case 16: return 2.74;
    case 32: return 3.50;
    default: return 0.0;
    }
}

// The scene with CCT on the object named `only` and no caching elsewhere.
Scene cachingOnly(Scene scene, const std::string& only) {
    for (SceneObject& o : scene.objects)
        o.material.cache.technique = o.name == only ? CacheTechnique::Cct : CacheTechnique::None;
    return scene;
}

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options{"Hybrid raster + ray tracing pipeline vs ray pipeline, interleaved frame timing"};
    int size = 1024, rounds = 7, warmup = 2, threads = 0;
    std::string parts = "abc";
    std::vector<std::string> scenes;
    for (const BuiltinSceneInfo& info : builtinScenes()) scenes.push_back(info.name);
    options.add("--size", size, "Image width and height");
    options.add("--rounds", rounds, "Timed frames per variant");
    options.add("--warmup", warmup, "Untimed frames per variant first (they fill the caches)");
    options.addThreads(threads);
    options.add("--scenes", scenes, "Built-in scenes for parts (a) and (b)");
    options.add("--parts", parts, "Which tables: any of a, b, c");
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;
    const Parallel parallel(threads);
    const std::optional<BenchmarkRecord> record =
        BenchmarkRecord::open("hybrid_speed", argc, argv, jsonPath, parallel.threadCount());
    if (!record) return 2;
    nlohmann::json gbufferOnly = nlohmann::json::array(), wholeFrames = nlohmann::json::array(),
                   table51 = nlohmann::json::array();
    Image film;

    std::string whyNot;
    {
        const Scene probe = *makeBuiltinScene("behind-0");
        if (!GBufferRasterizer::create(probe, whyNot)) {
            std::fprintf(stderr, "error: no OpenGL 4.5 core context: %s\n", whyNot.c_str());
            return 1;
        }
    }

    if (parts.find('a') != std::string::npos) {
        std::printf("## (a) G-buffer only, %dx%d: OpenGL vs primary-ray packets, ms\n\n", size, size);
        std::printf("| scene | OpenGL total | of it raster | of it readback | packets | OpenGL / packets |\n");
        std::printf("| --- | --- | --- | --- | --- | --- |\n");
        for (const std::string& name : scenes) {
            const auto scene = makeBuiltinScene(name);
            if (!scene) {
                std::fprintf(stderr, "error: unknown scene %s\n", name.c_str());
                return 2;
            }
            const TraceScene tracer(*scene);
            auto rasterizer = GBufferRasterizer::create(*scene, whyNot);
            const PacketGBuffer packets(*scene, tracer, parallel, 16);
            GBufferStorage storage;
            std::vector<double> rasterMs, readbackMs;
            int run = 0;
            const auto times = runInterleaved(
                {{"opengl",
                  [&] {
                      RasterTimes t;
                      rasterizer->rasterize(scene->camera, size, size, t);
                      if (run++ >= warmup) {
                          rasterMs.push_back(t.raster);
                          readbackMs.push_back(t.readback);
                      }
                      return std::uint64_t{0};
                  }},
                 {"packets", [&] { return packets.fill(scene->camera, size, size, storage); }}},
                warmup, rounds);
            std::printf("| %s | %s | %s | %s | %s | %.2f |\n", name.c_str(), range(times[0]).c_str(),
                        range(rasterMs).c_str(), range(readbackMs).c_str(), range(times[1]).c_str(),
                        times[0].median() / times[1].median());
            std::fflush(stdout);
            gbufferOnly.push_back({{"scene", name},
                                   {"opengl", benchmarkVariantJson(times[0])},
                                   {"opengl_raster", summaryJson(rasterMs)},
                                   {"opengl_readback", summaryJson(readbackMs)},
                                   {"packets", benchmarkVariantJson(times[1])},
                                   {"opengl_over_packets", times[0].median() / times[1].median()}});
        }
        std::printf("\n");
    }

    if (parts.find('b') != std::string::npos) {
        std::printf("## (b) whole frames, %dx%d, no caches: ray vs hybrid, ms\n\n", size, size);
        std::printf("| scene | ray | hybrid (OpenGL) | hybrid (packets) | ray / hybrid (OpenGL) | ray / hybrid "
                    "(packets) | hybrid (OpenGL) phases: raster, readback, shadows, secondary, compose |\n");
        std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
        for (const std::string& name : scenes) {
            const auto scene = makeBuiltinScene(name);
            if (!scene) return 2;
            const TraceScene tracer(*scene);
            const RenderSettings raySettings = settingsFor(size, threads, PipelineKind::Ray, GBufferSource::Auto);
            const RenderSettings glSettings = settingsFor(size, threads, PipelineKind::Hybrid, GBufferSource::OpenGl);
            const RenderSettings packetSettings =
                settingsFor(size, threads, PipelineKind::Hybrid, GBufferSource::Packets);
            auto ray = makeFramePipeline(*scene, tracer, raySettings, parallel);
            auto gl = makeFramePipeline(*scene, tracer, glSettings, parallel);
            auto packets = makeFramePipeline(*scene, tracer, packetSettings, parallel);
            std::vector<PhaseTimes> phases;
            const auto times = runInterleaved(
                {{"ray", [&] { return ray->render(scene->camera, film).rays.total(); }},
                 {"gl",
                  [&] {
                      const FrameStats s = gl->render(scene->camera, film);
                      phases.push_back(*s.phases);
                      return s.rays.total();
                  }},
                 {"packets", [&] { return packets->render(scene->camera, film).rays.total(); }}},
                warmup, rounds);
            std::vector<double> ph[5];
            for (std::size_t i = static_cast<std::size_t>(warmup); i < phases.size(); ++i) {
                ph[0].push_back(phases[i].raster);
                ph[1].push_back(phases[i].readback);
                ph[2].push_back(phases[i].shadows);
                ph[3].push_back(phases[i].secondary);
                ph[4].push_back(phases[i].compose);
            }
            std::printf("| %s | %s | %s | %s | %.2fx | %.2fx | %.1f, %.1f, %.1f, %.1f, %.1f |\n", name.c_str(),
                        range(times[0]).c_str(), range(times[1]).c_str(), range(times[2]).c_str(),
                        times[0].median() / times[1].median(), times[0].median() / times[2].median(),
                        summarize(ph[0]).median, summarize(ph[1]).median, summarize(ph[2]).median,
                        summarize(ph[3]).median, summarize(ph[4]).median);
            std::fflush(stdout);
            wholeFrames.push_back({{"scene", name},
                                   {"ray", benchmarkVariantJson(times[0])},
                                   {"hybrid_opengl", benchmarkVariantJson(times[1])},
                                   {"hybrid_packets", benchmarkVariantJson(times[2])},
                                   {"ray_over_hybrid_opengl", times[0].median() / times[1].median()},
                                   {"ray_over_hybrid_packets", times[0].median() / times[2].median()},
                                   {"hybrid_opengl_phases",
                                    {{"raster", summaryJson(ph[0])},
                                     {"readback", summaryJson(ph[1])},
                                     {"shadows", summaryJson(ph[2])},
                                     {"secondary", summaryJson(ph[3])},
                                     {"compose", summaryJson(ph[4])}}}});
        }
        std::printf("\n");
    }

    if (parts.find('c') != std::string::npos) {
        std::printf("## (c) Table 5.1 in the hybrid pipeline (OpenGL G-buffer), behind-N, %dx%d, 512^2 faces, "
                    "still camera, caches filled, ms\n\n",
                    size, size);
        std::printf("| N | hybrid | hybrid + CCT (main sphere) | hybrid + CCT (all mirrors) | speed-up (main) | "
                    "speed-up (all) | documents | ray (uncached), for reference |\n");
        std::printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
        for (const int n : {0, 1, 2, 4, 8, 16, 32}) {
            const Scene scene = *makeBuiltinScene("behind-" + std::to_string(n));
            const Scene mainOnly = cachingOnly(scene, "main");
            const TraceScene tracer(scene);
            RenderSettings plainSettings = settingsFor(size, threads, PipelineKind::Hybrid, GBufferSource::OpenGl);
            RenderSettings mainSettings = plainSettings;
            mainSettings.cache.techniqueOverride.reset();  // the materials say: main sphere only
            RenderSettings allSettings = plainSettings;
            allSettings.cache.techniqueOverride = CacheTechnique::Cct;
            const RenderSettings raySettings = settingsFor(size, threads, PipelineKind::Ray, GBufferSource::Auto);
            RayCache mainCache(mainOnly, mainSettings.cache), allCache(scene, allSettings.cache);
            auto plain = makeFramePipeline(scene, tracer, plainSettings, parallel);
            auto mainCct = makeFramePipeline(mainOnly, tracer, mainSettings, parallel, &mainCache);
            auto allCct = makeFramePipeline(scene, tracer, allSettings, parallel, &allCache);
            auto ray = makeFramePipeline(scene, tracer, raySettings, parallel);
            const auto times = runInterleaved(
                {{"hybrid", [&] { return plain->render(scene.camera, film).rays.total(); }},
                 {"hybrid+cct main", [&] { return mainCct->render(scene.camera, film).rays.total(); }},
                 {"hybrid+cct all", [&] { return allCct->render(scene.camera, film).rays.total(); }},
                 {"ray", [&] { return ray->render(scene.camera, film).rays.total(); }}},
                warmup, rounds);
            std::printf("| %d | %s | %s | %s | %.2fx | %.2fx | %.2fx | %s |\n", n, range(times[0]).c_str(),
                        range(times[1]).c_str(), range(times[2]).c_str(), times[0].median() / times[1].median(),
                        times[0].median() / times[2].median(), documentsBehindSpeedup(n), range(times[3]).c_str());
            std::fflush(stdout);
            table51.push_back({{"n", n},
                               {"hybrid", benchmarkVariantJson(times[0])},
                               {"hybrid_cct_main", benchmarkVariantJson(times[1])},
                               {"hybrid_cct_all", benchmarkVariantJson(times[2])},
                               {"ray", benchmarkVariantJson(times[3])},
                               {"speedup_main", times[0].median() / times[1].median()},
                               {"speedup_all", times[0].median() / times[2].median()},
                               {"documents_speedup", documentsBehindSpeedup(n)}});
        }
    }
    return record->write({{"size", size},
                          {"rounds", rounds},
                          {"warmup", warmup},
                          {"threads", threads},
                          {"worker_threads", parallel.threadCount()},
                          {"scenes", scenes},
                          {"parts", parts}},
                         {{"gbuffer_only", gbufferOnly}, {"whole_frames", wholeFrames}, {"table_5_1", table51}});
}
