// CDCT measured two ways, side by side in one run:
//  quality: the `parallax` camera path (from empty caches) against the
//           uncached frames: PSNR per frame for CCT, CDCT parity and the
//           improved CDCT with its changes switched on one after another;
//  speed:   the thesis's Table 5.3 (diffuse-32, reflective-32 at 1920x1080,
//           still camera, caches filled by the warm-up frames): CCT,
//           uncached, CDCT parity at the four delta/epsilon pairs and the
//           improved CDCT, then the improved CDCT's changes one by one.
// With --json FILE it also writes every figure of the tables it prints, with
// the run's settings, machine and build, as one JSON document
// (bench/BenchmarkRecord.h; the docs quote the runs in docs/bench-runs/cdct_speed/).
// Usage: cdct_speed [--quality-only | --speed-only] [--width 1920 --height 1080] [--rounds 5] [--json FILE]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
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
#include "scene/Material.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

struct CacheVariant {
    std::string name;
    CacheTechnique technique;
    CdctImprovements improvements{};
    float step = 0.4f, epsilon = 0.05f;  // parity search
};

// The improved CDCT's changes, switched on one after another (each row adds one).
std::vector<CacheVariant> improvementLadder() {
    CdctImprovements i{false, false, false, false, false, false, false, false, false};
    std::vector<CacheVariant> rows;
    i.prefill = true;
    rows.push_back({"+ pre-fill (fixed 0.4/0.05 steps)", CacheTechnique::Cdct, i});
    i.texelSteps = true;
    rows.push_back({"+ texel-space steps", CacheTechnique::Cdct, i});
    i.earlyExit = true;
    rows.push_back({"+ early exit", CacheTechnique::Cdct, i});
    i.skipEmptySpace = true;
    rows.push_back({"+ empty-space skipping", CacheTechnique::Cdct, i});
    i.errorControl = true;
    rows.push_back({"+ error control", CacheTechnique::Cdct, i});
    i.filter = true;
    rows.push_back({"+ filtering", CacheTechnique::Cdct, i});
    i.traceViewDependent = true;
    rows.push_back({"+ mirrors and glass seen from the centre traced", CacheTechnique::Cdct, i});
    i.traceOwnSurface = true;
    rows.push_back({"+ rays meeting their own object traced", CacheTechnique::Cdct, i});
    i.faceWalk = true;
    rows.push_back({"+ texels walked face by face (= cdct)", CacheTechnique::Cdct, i});
    return rows;
}

// A float option as it was written (0.2, not 0.200000003).
double asWritten(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(value));
    return std::strtod(text, nullptr);
}

// What a variant is, for the JSON: its row's name, its technique, the parity
// search's steps, and how many of the improved CDCT's changes are on.
nlohmann::json variantJson(const CacheVariant& v) {
    nlohmann::json json = {{"name", v.name}, {"technique", cacheTechniqueName(v.technique)}};
    if (v.technique == CacheTechnique::CdctParity) {
        json["step"] = asWritten(v.step);
        json["epsilon"] = asWritten(v.epsilon);
    }
    if (v.technique == CacheTechnique::Cdct) {
        const CdctImprovements& i = v.improvements;
        json["improvements_on"] = int{i.prefill} + i.texelSteps + i.earlyExit + i.skipEmptySpace + i.errorControl +
                                  i.filter + i.traceViewDependent + i.traceOwnSurface + i.faceWalk;
    }
    return json;
}

// The cubes' face resolution: the one asked for, else the largest the scene's objects ask for.
int faceResolution(const Scene& scene, std::optional<int> resolution) {
    if (resolution) return *resolution;
    int largest = 0;
    for (const SceneObject& o : scene.objects) largest = std::max(largest, o.material.cache.faceResolution);
    return largest;
}

RenderSettings settingsFor(int width, int height, int threads, const CacheVariant& v, std::optional<int> resolution) {
    RenderSettings s;
    s.width = width;
    s.height = height;
    s.threads = threads;
    s.cache.techniqueOverride = v.technique;
    s.cache.cdctImprovements = v.improvements;
    s.cache.cdctStepOverride = v.step;
    s.cache.cdctEpsilonOverride = v.epsilon;
    s.cache.resolutionOverride = resolution;
    return s;
}

// One scene's quality table; returns its rows as printed.
nlohmann::json quality(const std::string& sceneName, int size, int frames, int threads, std::optional<int> resolution,
                       const Parallel& parallel) {
    const auto scene = makeBuiltinScene(sceneName);
    if (!scene) throw std::invalid_argument("no built-in scene named '" + sceneName + "'");
    const TraceScene tracer(*scene);
    std::vector<CacheVariant> variants{{"CCT", CacheTechnique::Cct}, {"CDCT parity 0.4/0.05", CacheTechnique::CdctParity}};
    const std::size_t ladderStart = variants.size();
    for (const CacheVariant& v : improvementLadder()) variants.push_back(v);

    const CacheVariant none{"uncached", CacheTechnique::None};
    const RenderSettings plainSettings = settingsFor(size, size, threads, none, resolution);
    const FrameRenderer plain(*scene, tracer, plainSettings, parallel);
    std::vector<Image> truth(static_cast<std::size_t>(frames));
    for (int f = 0; f < frames; ++f) plain.render(scene->cameraPath.cameraAt(scene->camera, f), truth[static_cast<std::size_t>(f)]);

    std::printf("## quality: %s %dx%d, %d frames of its camera path from empty caches, faces %s\n\n",
                sceneName.c_str(), size, size, frames, resolution ? std::to_string(*resolution).c_str() : "512 (scene)");
    std::printf("| variant | mean PSNR frames 2-%d (dB) | min | last frame | hit rate | rejected |\n", frames);
    std::printf("| --- | --- | --- | --- | --- | --- |\n");
    nlohmann::json rows = nlohmann::json::array(), ladder = nlohmann::json::array();
    for (std::size_t row = 0; row < variants.size(); ++row) {
        const CacheVariant& v = variants[row];
        const RenderSettings settings = settingsFor(size, size, threads, v, resolution);
        RayCache cache(*scene, settings.cache);
        const FrameRenderer renderer(*scene, tracer, settings, parallel, &cache);
        double sum = 0.0, lowest = 1e9, last = 0.0;
        std::uint64_t lookups = 0, hits = 0, rejected = 0;
        for (int f = 0; f < frames; ++f) {
            Image film;
            const FrameStats stats = renderer.render(scene->cameraPath.cameraAt(scene->camera, f), film);
            if (f == 0) continue;  // the first frame traces everything in every variant
            // Identical frames (nothing answered from the cache) count as 100 dB.
            const double db = std::min(100.0, psnr(film, truth[static_cast<std::size_t>(f)]));
            sum += db;
            lowest = std::min(lowest, db);
            last = db;
            lookups += stats.cache->lookups();
            hits += stats.cache->hits();
            rejected += stats.cache->rejected();
        }
        const double n = static_cast<double>(lookups ? lookups : 1);
        const double mean = sum / (frames - 1), hitPercent = 100.0 * static_cast<double>(hits) / n,
                     rejectedPercent = 100.0 * static_cast<double>(rejected) / n;
        std::printf("| %s | %.2f | %.2f | %.2f | %.1f%% | %.1f%% |\n", v.name.c_str(), mean, lowest, last, hitPercent,
                    rejectedPercent);
        std::fflush(stdout);
        nlohmann::json json = variantJson(v);
        json.update({{"mean_psnr_db", finiteOrNull(mean)},
                     {"min_psnr_db", finiteOrNull(lowest)},
                     {"last_psnr_db", finiteOrNull(last)},
                     {"hit_percent", hitPercent},
                     {"rejected_percent", rejectedPercent}});
        (row < ladderStart ? rows : ladder).push_back(json);
    }
    return {{"scene", sceneName},
            {"size", size},
            {"frames", frames},
            {"face_resolution", faceResolution(*scene, resolution)},
            {"variants", rows},
            {"improvements_one_by_one", ladder}};
}

// The thesis's Table 5.3, frames per second.
struct DocumentsRow {
    const char* scene;
    double fps[6];  // CCT, standard RT, CDCT 2/0.2, 0.4/0.05, 0.2/0.02, 0.02/0.002
};
constexpr DocumentsRow kTable53[] = {{"diffuse-32", {76.0, 69.6, 49.5, 35.3, 30.7, 19.0}},
                                     {"reflective-32", {33.9, 30.1, 19.1, 17.0, 13.5, 13.9}}};

// Table 5.3's speed tables, one a scene; returns their rows as printed.
nlohmann::json speed(int width, int height, int threads, int warmup, int rounds, std::optional<int> resolution,
                     const Parallel& parallel) {
    nlohmann::json tables = nlohmann::json::array();
    for (const DocumentsRow& row : kTable53) {
        const auto scene = makeBuiltinScene(row.scene);
        const TraceScene tracer(*scene);
        std::vector<CacheVariant> variants{{"CCT", CacheTechnique::Cct},
                                           {"uncached", CacheTechnique::None},
                                           {"CDCT parity 2/0.2", CacheTechnique::CdctParity, {}, 2.0f, 0.2f},
                                           {"CDCT parity 0.4/0.05", CacheTechnique::CdctParity, {}, 0.4f, 0.05f},
                                           {"CDCT parity 0.2/0.02", CacheTechnique::CdctParity, {}, 0.2f, 0.02f},
                                           {"CDCT parity 0.02/0.002", CacheTechnique::CdctParity, {}, 0.02f, 0.002f},
                                           {"CDCT improved (cdct)", CacheTechnique::Cdct}};
        const std::size_t tableRows = variants.size();
        for (const CacheVariant& v : improvementLadder()) variants.push_back(v);

        std::vector<RenderSettings> settings;
        std::vector<std::unique_ptr<RayCache>> caches;
        std::vector<std::unique_ptr<FrameRenderer>> renderers;
        std::vector<double> hitPercent(variants.size(), 0.0);
        std::vector<Variant> runs;
        Image film;
        for (std::size_t i = 0; i < variants.size(); ++i) {
            settings.push_back(settingsFor(width, height, threads, variants[i], resolution));
        }
        for (std::size_t i = 0; i < variants.size(); ++i) {
            caches.push_back(std::make_unique<RayCache>(*scene, settings[i].cache));
            renderers.push_back(
                std::make_unique<FrameRenderer>(*scene, tracer, settings[i], parallel, caches[i].get()));
            runs.push_back({variants[i].name, [&, i] {
                                const FrameStats stats = renderers[i]->render(scene->camera, film);
                                if (stats.cache && stats.cache->lookups())
                                    hitPercent[i] = 100.0 * static_cast<double>(stats.cache->hits()) /
                                                    static_cast<double>(stats.cache->lookups());
                                return stats.rays.total();
                            }});
        }
        const auto times = runInterleaved(runs, warmup, rounds);
        const double uncached = times[1].median();
        std::printf("\n## speed: %s %dx%d, still camera, caches filled by %d warm-up frames, %d timed rounds\n\n",
                    row.scene, width, height, warmup, rounds);
        std::printf("| variant | ms median (min-max) | fps | speed-up vs uncached | hit rate | documents fps | "
                    "documents speed-up |\n");
        std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
        nlohmann::json rows = nlohmann::json::array(), ladder = nlohmann::json::array();
        for (std::size_t i = 0; i < variants.size(); ++i) {
            if (i == tableRows) std::printf("| *improved CDCT, changes one by one* | | | | | | |\n");
            char documents[64] = "", documentsRatio[32] = "";
            if (i < 6) {
                std::snprintf(documents, sizeof documents, "%.1f", row.fps[i]);
                std::snprintf(documentsRatio, sizeof documentsRatio, "%.2fx", row.fps[i] / row.fps[1]);
            }
            const VariantTimes& t = times[i];
            std::printf("| %s | %.1f (%.1f-%.1f) | %.1f | %.2fx | %.1f%% | %s | %s |\n", variants[i].name.c_str(),
                        t.median(), t.min(), t.max(), 1000.0 / t.median(), uncached / t.median(), hitPercent[i],
                        documents, documentsRatio);
            nlohmann::json json = variantJson(variants[i]);
            json.update(benchmarkVariantJson(t));
            json.update({{"speedup_vs_uncached", uncached / t.median()},
                         {"hit_percent", hitPercent[i]},
                         {"documents_fps", i < 6 ? nlohmann::json(row.fps[i]) : nlohmann::json()},
                         {"documents_speedup", i < 6 ? nlohmann::json(row.fps[i] / row.fps[1]) : nlohmann::json()}});
            (i < tableRows ? rows : ladder).push_back(json);
        }
        std::fflush(stdout);
        tables.push_back({{"scene", row.scene},
                          {"width", width},
                          {"height", height},
                          {"face_resolution", faceResolution(*scene, resolution)},
                          {"variants", rows},
                          {"improvements_one_by_one", ladder}});
    }
    return tables;
}

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options{"CDCT: quality on parallax and Table 5.3 speed, every variant side by side"};
    int width = 1920, height = 1080, rounds = 5, warmup = 2, threads = 0, qualitySize = 256, qualityFrames = 25;
    std::optional<int> resolution;
    bool qualityOnly = false, speedOnly = false;
    options.add("--width", width, "Speed: image width");
    options.add("--height", height, "Speed: image height");
    options.add("--rounds", rounds, "Speed: timed frames per variant");
    options.add("--warmup", warmup, "Speed: untimed frames per variant first (they fill the caches)");
    options.add("--quality-size", qualitySize, "Quality: image width and height");
    options.add("--quality-frames", qualityFrames, "Quality: frames of each scene's camera path");
    std::vector<std::string> qualityScenes{"parallax"};
    options.add("--quality-scenes", qualityScenes, "Quality: built-in scenes, each its own table");
    options.add("--cache-res", resolution, "Face resolution for every cube (default: the scenes' own, 512)",
                BenchmarkOptions::Range{CacheSettings::kMinFaceResolution, CacheSettings::kMaxFaceResolution});
    options.addThreads(threads);
    options.flag("--quality-only", qualityOnly, "Only the quality table");
    options.flag("--speed-only", speedOnly, "Only the speed tables");
    std::filesystem::path jsonPath;
    options.addJson(jsonPath);
    if (const std::optional<int> exitCode = options.parse(argc, argv)) return *exitCode;
    // Every scene named is checked before anything is measured.
    if (!speedOnly)
        for (const std::string& name : qualityScenes)
            if (!makeBuiltinScene(name)) {
                std::fprintf(stderr, "cdct_speed: --quality-scenes: no built-in scene named '%s'\n", name.c_str());
                return 2;
            }
    const Parallel parallel(threads);
    const std::optional<BenchmarkRecord> record =
        BenchmarkRecord::open("cdct_speed", argc, argv, jsonPath, parallel.threadCount());
    if (!record) return 2;
    nlohmann::json qualityTables = nlohmann::json::array(), speedTables = nlohmann::json::array();
    nlohmann::json parts = nlohmann::json::array();
    if (!speedOnly) {
        parts.push_back("quality");
        for (const std::string& name : qualityScenes) {
            qualityTables.push_back(quality(name, qualitySize, qualityFrames, threads, resolution, parallel));
            std::printf("\n");
        }
    }
    if (!qualityOnly) {
        parts.push_back("speed");
        speedTables = speed(width, height, threads, warmup, rounds, resolution, parallel);
    }
    return record->write({{"width", width},
                          {"height", height},
                          {"rounds", rounds},
                          {"warmup", warmup},
                          {"threads", threads},
                          {"worker_threads", parallel.threadCount()},
                          {"quality_size", qualitySize},
                          {"quality_frames", qualityFrames},
                          {"quality_scenes", qualityScenes},
                          {"cache_res", resolution ? nlohmann::json(*resolution) : nlohmann::json()},
                          {"parts", parts}},
                         {{"quality", qualityTables}, {"speed", speedTables}});
}
