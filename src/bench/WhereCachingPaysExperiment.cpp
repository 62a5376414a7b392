#include "bench/WhereCachingPaysExperiment.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <cmath>
#include <optional>

#include "bench/CachingPayModel.h"
#include "bench/InterleavedRuns.h"
#include "bench/MarkdownTable.h"
#include "bench/ResultsJson.h"
#include "bench/SpeedupInterval.h"
#include "bench/SvgPlot.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/SampleSummary.h"
#include "render/CameraRays.h"
#include "scene/BuiltinScenes.h"
#include "scene/MeshSearchPath.h"
#include "scene/RealMeshScenes.h"
#include "session/RenderSession.h"
#include "trace/TraceScene.h"

namespace raycache {

namespace {

struct PaySize {
    int width = 0, height = 0;
    int warmupFrames = 0;     // still camera, untimed: the caches fill
    int timedFrames = 0;      // still camera, variants interleaved
    int pathFrames = 0;       // camera path (and animation) from empty caches
    int cacheResolution = 0;  // cube faces; 0: each scene's own
    std::vector<std::string> scenes;
};

// Every built-in scene with mirrors or glass, the animated ones, and those
// made of real meshes.
const std::vector<std::string>& allScenes() {
    static const std::vector<std::string> scenes = {
        "grid-8",  "grid-32", "behind-32", "reflective-32", "diffuse-32", "room",        "glass",
        "shapes",  "parallax", "bowl",     "room-moving",   "orbit",      "light-sweep", "cloth",
        "bunny-glass", "teapot-mirrors", "dragon-hall", "dragon-mirrors"};
    return scenes;
}

PaySize sizeFor(BenchSize size) {
    switch (size) {
        // Four warm-up frames: under `auto` a cube samples for two frames and
        // fills in the third (cache/CachePolicy.h) before it is filled.
        case BenchSize::Full: return {1024, 1024, 4, 7, 20, 0, allScenes()};
        case BenchSize::Quick: return {384, 384, 4, 5, 10, 256, allScenes()};
        case BenchSize::Tiny: break;
    }
    return {32, 32, 1, 1, 2, 32, {"grid-8", "orbit"}};
}

// CCT and CDCT cache every frame (`always`), as the model assumes; "CCT
// auto" is CCT under the CLI's default policy (cache/CachePolicy.h), whose
// cubes stand aside while caching would cost more than it saves.
enum VariantIndex : std::size_t { kUncached, kIdeal, kCct, kCdct, kCctAuto, kVariants };
const char* const kVariantNames[kVariants] = {"uncached", "ideal cache", "CCT", "CDCT", "CCT auto"};
// Rough cost of a frame relative to uncached, for the progress bar.
const double kVariantCost[kVariants] = {1.0, 0.8, 1.0, 3.0, 1.0};

// What a variant's frames did in one part of the run (still or path).
struct FrameTotals {
    std::vector<double> ms;  // wall time per timed frame
    double lookupCpuMs = 0.0;  // the reuse-lookup stage
    // The secondary-ray stage, where CCT lookups are asked as the rays
    // spawn (render/TileKernelWaves.cpp), and the hits it spawned from.
    double spawnCpuMs = 0.0;
    std::uint64_t hitsShaded = 0;
    double frameEndMs = 0.0;  // wall
    std::uint64_t lookups = 0, hits = 0;
    // The policy's: cubes x frames, and those stood aside or sampling.
    std::uint64_t cubeFrames = 0, bypassedCubeFrames = 0, samplingCubeFrames = 0;
    int frames = 0;

    void add(const FrameStats& stats) {
        ++frames;
        if (stats.stages) {
            lookupCpuMs += stats.stages->reuseLookups;
            spawnCpuMs += stats.stages->secondaryRays;
            hitsShaded += stats.stages->hitsShaded;
            frameEndMs += stats.stages->cacheFrameEnd;
        }
        if (stats.cache) {
            lookups += stats.cache->lookups();
            hits += stats.cache->hits();
            cubeFrames += stats.cache->objects.size();
            bypassedCubeFrames += static_cast<std::uint64_t>(stats.cache->bypassedCubes());
            samplingCubeFrames += static_cast<std::uint64_t>(stats.cache->samplingCubes());
        }
    }
    // The lookups' wall ms a frame: the reuse-lookup stage plus what the
    // secondary-ray stage took over the uncached frame's, scaled by the hits
    // spawned from (lookups are asked where the rays spawn; without this the
    // model sees no cost for them and misses the measured speed-ups).
    double meanLookupWallMs(int threads, const FrameTotals& uncached) const {
        if (frames == 0) return 0.0;
        const auto perFrame = [](double total, int n) { return n > 0 ? total / n : 0.0; };
        const double spawnedFrom = perFrame(static_cast<double>(hitsShaded), frames);
        const double uncachedHits = perFrame(static_cast<double>(uncached.hitsShaded), uncached.frames);
        const double ratio = uncachedHits > 0.0 ? spawnedFrom / uncachedHits : 1.0;
        const double atSpawn =
            std::max(0.0, perFrame(spawnCpuMs, frames) - ratio * perFrame(uncached.spawnCpuMs, uncached.frames));
        return (perFrame(lookupCpuMs, frames) + atSpawn) / std::max(threads, 1);
    }
    double bypassedShare() const {
        return cubeFrames > 0 ? static_cast<double>(bypassedCubeFrames) / static_cast<double>(cubeFrames) : 0.0;
    }
    double samplingShare() const {
        return cubeFrames > 0 ? static_cast<double>(samplingCubeFrames) / static_cast<double>(cubeFrames) : 0.0;
    }
    double meanFrameEndMs() const { return frames > 0 ? frameEndMs / frames : 0.0; }
    double hitRate() const { return lookups > 0 ? static_cast<double>(hits) / static_cast<double>(lookups) : 0.0; }
    double meanLookups() const { return frames > 0 ? static_cast<double>(lookups) / frames : 0.0; }
};

double meanMs(const std::vector<double>& v) {
    double sum = 0.0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

// One technique on one scene: measured and predicted, still and along the path.
struct TechniqueRow {
    SpeedupInterval stillMeasured, pathMeasured;
    CachingPayParts stillParts, pathParts;
    double stillPredicted = 0.0, pathPredicted = 0.0;
};

struct SceneRow {
    std::string scene;
    bool animated = false;
    double coverage = 0.0;  // share of the image whose first hit is a mirror or glass
    double stillShare = 0.0, pathShare = 0.0;
    TechniqueRow cct, cdct;
    SpeedupInterval autoStill, autoPath;  // CCT under `--cache-policy auto`
    double autoBypassedShare = 0.0;       // of the cube-frames along the path, stood aside
    double autoSamplingShare = 0.0;       // of the cube-frames along the path, sampling
};

// Share of the pixels (on a grid of at most 128 x 128) whose camera ray
// first meets a mirror or glass.
double mirrorGlassCoverage(const Scene& scene, const TraceScene& tracer, const Camera& camera, int width, int height) {
    const int columns = std::min(width, 128), rows = std::min(height, 128);
    const CameraRays rays(camera, width, height);
    int covered = 0;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const TraceHit hit = tracer.intersect(rays.ray(i * width / columns, j * height / rows));
            if (!hit.hit()) continue;
            const Material& m = scene.objects[static_cast<std::size_t>(hit.objectId)].material;
            if (m.reflects() || m.refracts()) ++covered;
        }
    return static_cast<double>(covered) / (static_cast<double>(columns) * rows);
}

double relativeError(double predicted, double measured) {
    return measured > 0.0 && std::isfinite(measured) ? predicted / measured - 1.0 : std::nan("");
}

std::string errorCell(double error) {
    if (!std::isfinite(error)) return "–";
    return (error >= 0.0 ? "+" : "") + cellNumber(100.0 * error, 0) + " %";
}

nlohmann::json partsJson(const CachingPayParts& p) {
    return {{"uncached_ms", finiteOrNull(p.uncachedMs)},
            {"ideal_ms", finiteOrNull(p.idealMs)},
            {"ideal_lookup_ms", finiteOrNull(p.idealLookupMs)},
            {"lookup_ms", finiteOrNull(p.lookupMs)},
            {"frame_end_ms", finiteOrNull(p.frameEndMs)},
            {"hit_rate", finiteOrNull(p.hitRate)},
            {"leaving_rays", p.leavingRays},
            {"cacheable_tree_ms", finiteOrNull(cacheableTreeMs(p))},
            {"cacheable_share", finiteOrNull(cacheableShare(p))},
            {"free_cache_speedup", finiteOrNull(freeCacheSpeedup(p))}};
}

nlohmann::json techniqueJson(const TechniqueRow& t) {
    return {{"still",
             {{"measured", toJson(t.stillMeasured)},
              {"predicted", finiteOrNull(t.stillPredicted)},
              {"error", finiteOrNull(relativeError(t.stillPredicted, t.stillMeasured.speedup))},
              {"parts", partsJson(t.stillParts)}}},
            {"path",
             {{"measured", toJson(t.pathMeasured)},
              {"predicted", finiteOrNull(t.pathPredicted)},
              {"error", finiteOrNull(relativeError(t.pathPredicted, t.pathMeasured.speedup))},
              {"parts", partsJson(t.pathParts)}}}};
}

class WhereCachingPaysExperiment final : public Experiment {
public:
    std::string name() const override { return "where-caching-pays"; }
    std::string title() const override {
        return "Where caching pays: CCT and CDCT against uncached, measured and modelled, per scene";
    }
    // It times CCT under both policies whatever `bench --cache-policy` says,
    // so no note that the option was not applied.
    bool honoursCachePolicy() const override { return true; }
    double estimatedWork(const BenchSettings& settings) const override {
        const PaySize s = sizeFor(settings.size);
        double perScene = 0.0;
        for (double cost : kVariantCost)
            perScene += cost * (s.warmupFrames + s.timedFrames + s.pathFrames);
        return perScene * static_cast<double>(s.width) * s.height / 1e6 * static_cast<double>(s.scenes.size());
    }

    ExperimentOutput run(ExperimentContext& context) const override {
        const PaySize size = sizeFor(context.settings.size);
        const double megapixels = static_cast<double>(size.width) * size.height / 1e6;
        const int threads = context.parallel.threadCount();
        const MeshSearchPath meshes = meshSearchPathFromEnvironment();
        ExperimentOutput out;
        out.name = name();
        out.title = title();
        std::vector<SceneRow> rows;
        nlohmann::json rowsJson = nlohmann::json::array();

        for (const std::string& sceneName : size.scenes) {
            context.progress.step(name() + ": " + sceneName);
            std::optional<Scene> maybeScene = makeBuiltinScene(sceneName);
            if (!maybeScene) {
                const auto real = realMeshScenes();
                const auto info = std::find_if(real.begin(), real.end(),
                                               [&](const RealMeshSceneInfo& r) { return r.name == sceneName; });
                if (info == real.end()) throw RuntimeError("scene " + sceneName + " is missing");
                if (const std::string missing = missingMeshFiles(*info, meshes); !missing.empty()) {
                    out.caveats.push_back(sceneName + " left out: its mesh is not on the search path (" + missing +
                                          "; scripts/install-deps.sh fetches it)");
                    context.progress.advance(estimatedWork(context.settings) / static_cast<double>(size.scenes.size()));
                    continue;
                }
                maybeScene = makeRealMeshScene(sceneName, meshes);
            }
            const Scene scene = std::move(*maybeScene);
            rows.push_back(measureScene(context, size, scene, sceneName, threads, megapixels));
            rowsJson.push_back({{"scene", rows.back().scene},
                                {"animated", rows.back().animated},
                                {"mirror_glass_coverage", rows.back().coverage},
                                {"cct", techniqueJson(rows.back().cct)},
                                {"cdct", techniqueJson(rows.back().cdct)},
                                {"cct_auto",
                                 {{"still", toJson(rows.back().autoStill)},
                                  {"path", toJson(rows.back().autoPath)},
                                  {"path_bypassed_share", rows.back().autoBypassedShare},
                                  {"path_sampling_share", rows.back().autoSamplingShare}}}});
        }

        out.markdown = describe(size, rows, out);
        writeSvgPlot(plot(rows), (context.dir / "speedup-vs-share.svg").string());
        out.plots = {"speedup-vs-share.svg"};
        out.caveats.push_back(
            "the model leaves out queueing the stores, a miss's bookkeeping and the changed coherence of the rays "
            "still traced; its error shows them");
        const nlohmann::json root = {{"experiment", name()},
                                     {"title", title()},
                                     {"size", toString(context.settings.size)},
                                     {"settings",
                                      {{"width", size.width},
                                       {"height", size.height},
                                       {"warmup_frames", size.warmupFrames},
                                       {"timed_frames", size.timedFrames},
                                       {"path_frames", size.pathFrames},
                                       {"cache_resolution", size.cacheResolution},
                                       {"threads", threads}}},
                                     {"environment", toJson(context.environment)},
                                     {"caveats", out.caveats},
                                     {"rows", rowsJson}};
        writeJsonFile(context.dir / "results.json", root);
        writeTextFileAtomically(context.dir / "results.md", experimentMarkdown(out));
        return out;
    }

private:
    static SceneRow measureScene(ExperimentContext& context, const PaySize& size, const Scene& scene,
                                 const std::string& sceneName, int threads, double megapixels) {
        SceneRow row;
        row.scene = sceneName;
        row.animated = !scene.animation.empty();
        // Sessions of a still scene share one tracer; an animated scene's
        // each pose their own (a shared tracer cannot move).
        std::optional<TraceScene> shared;
        if (!row.animated) shared.emplace(scene);
        std::vector<std::unique_ptr<RenderSession>> sessions;
        for (std::size_t v = 0; v < kVariants; ++v) {
            RenderSettings s;
            s.width = size.width;
            s.height = size.height;
            s.threads = context.settings.threads;
            s.stageTimes = true;  // every variant pays the same two clock reads per stage
            s.cache.techniqueOverride = v == kUncached ? CacheTechnique::None
                                        : v == kCdct   ? CacheTechnique::Cdct
                                                       : CacheTechnique::Cct;
            s.cache.ideal = v == kIdeal;
            s.cache.policy = v == kCctAuto ? CachePolicyMode::Auto : CachePolicyMode::Always;
            if (size.cacheResolution > 0) s.cache.resolutionOverride = size.cacheResolution;
            sessions.push_back(shared ? std::make_unique<RenderSession>(scene, s, *shared, context.parallel)
                                      : std::make_unique<RenderSession>(scene, s));
        }
        {
            const TraceScene coverageTracer(scene);
            row.coverage = mirrorGlassCoverage(scene, coverageTracer, scene.camera, size.width, size.height);
        }

        // (a) Still camera at t = 0: warm-up frames fill the caches, then timed
        // frames, the variants interleaved. Every frame's stats are kept; the
        // timed ones are the last.
        Image film;
        std::array<std::vector<FrameStats>, kVariants> stillStats;
        std::vector<Variant> variants;
        for (std::size_t v = 0; v < kVariants; ++v)
            variants.push_back({kVariantNames[v],
                                [&, v] {
                                    stillStats[v].push_back(sessions[v]->render(scene.camera, film));
                                    return stillStats[v].back().rays.total();
                                },
                                {},
                                [&, v] { context.progress.advance(kVariantCost[v] * megapixels); }});
        const std::vector<VariantTimes> stillTimes = runInterleaved(variants, size.warmupFrames, size.timedFrames);
        std::array<FrameTotals, kVariants> still;
        for (std::size_t v = 0; v < kVariants; ++v) {
            const std::size_t timed = stillTimes[v].milliseconds.size();
            for (std::size_t k = stillStats[v].size() - std::min(timed, stillStats[v].size()); k < stillStats[v].size();
                 ++k)
                still[v].add(stillStats[v][k]);
            still[v].ms = stillTimes[v].milliseconds;
        }

        // (b) The camera path (and the animation) from empty caches, the
        // variants interleaved frame by frame.
        std::array<FrameTotals, kVariants> path;
        for (std::size_t v = 0; v < kVariants; ++v) sessions[v]->cache().clear();
        for (int f = 0; f < size.pathFrames; ++f) {
            const Camera camera = scene.cameraPath.cameraAt(scene.camera, f);
            for (std::size_t v = 0; v < kVariants; ++v) {
                if (row.animated) sessions[v]->setTime(static_cast<float>(f) / scene.fps);
                const auto start = std::chrono::steady_clock::now();
                const FrameStats stats = sessions[v]->render(camera, film);
                path[v].ms.push_back(
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
                path[v].add(stats);
                context.progress.advance(kVariantCost[v] * megapixels);
            }
        }

        const auto parts = [&](const std::array<FrameTotals, kVariants>& t, std::size_t technique, bool useMean) {
            CachingPayParts p;
            p.uncachedMs = useMean ? meanMs(t[kUncached].ms) : summarize(t[kUncached].ms).median;
            p.idealMs = useMean ? meanMs(t[kIdeal].ms) : summarize(t[kIdeal].ms).median;
            p.idealLookupMs = t[kIdeal].meanLookupWallMs(threads, t[kUncached]);
            p.lookupMs = t[technique].meanLookupWallMs(threads, t[kUncached]);
            p.frameEndMs = t[technique].meanFrameEndMs();
            p.hitRate = t[technique].hitRate();
            p.leavingRays = static_cast<std::uint64_t>(std::llround(t[kIdeal].meanLookups()));
            return p;
        };
        BootstrapSettings pathSettings;
        pathSettings.statistic = TimeStatistic::Mean;
        const auto fill = [&](TechniqueRow& r, std::size_t technique) {
            r.stillMeasured = bootstrapSpeedup(still[kUncached].ms, still[technique].ms);
            r.pathMeasured = bootstrapSpeedup(path[kUncached].ms, path[technique].ms, pathSettings);
            r.stillParts = parts(still, technique, false);
            r.pathParts = parts(path, technique, true);
            r.stillPredicted = predictedSpeedup(r.stillParts);
            r.pathPredicted = predictedSpeedup(r.pathParts);
        };
        fill(row.cct, kCct);
        fill(row.cdct, kCdct);
        row.autoStill = bootstrapSpeedup(still[kUncached].ms, still[kCctAuto].ms);
        row.autoPath = bootstrapSpeedup(path[kUncached].ms, path[kCctAuto].ms, pathSettings);
        row.autoBypassedShare = path[kCctAuto].bypassedShare();
        row.autoSamplingShare = path[kCctAuto].samplingShare();
        row.stillShare = cacheableShare(row.cct.stillParts);
        row.pathShare = cacheableShare(row.cct.pathParts);
        return row;
    }

    static std::string describe(const PaySize& size, const std::vector<SceneRow>& rows, ExperimentOutput& out) {
        std::string md =
            std::to_string(size.width) + "×" + std::to_string(size.height) + ", " +
            (size.cacheResolution > 0 ? std::to_string(size.cacheResolution) + "² cube faces"
                                      : std::string("each scene's cube faces")) +
            ", every mirror and glass object caching (`always`). *Filled*: a still camera, " +
            std::to_string(size.warmupFrames) + " warm-up and " + std::to_string(size.timedFrames) +
            " timed frames per variant, interleaved; medians. *Path*: the scene's camera path and animation, " +
            std::to_string(size.pathFrames) +
            " frames from empty caches, the variants interleaved frame by frame; means. Measured speed-up = "
            "uncached / technique, with its 95 % bootstrap interval. The model (bench/CachingPayModel.h): the "
            "cacheable share is the time an ideal cache (every ray leaving a mirror or glass looked up, none "
            "traced) saves, lookups given back; predicted frame = uncached − hit rate × cacheable trees + the "
            "technique's lookups + its frame-end work (the merge of stores, CDCT's pre-fill). Error = predicted / measured − 1. "
            "*Free cache*: the most any cache could gain, every tree answered with lookups and stores free, "
            "1 / (1 − cacheable share).\n\n";
        for (const auto& [label, pick] :
             {std::pair<const char*, TechniqueRow SceneRow::*>{"CCT", &SceneRow::cct}, {"CDCT", &SceneRow::cdct}}) {
            md += std::string("### ") + label + "\n\n";
            MarkdownTable t({"scene", "mirror/glass of image", "cacheable share (filled)",
                             "free cache (filled)", "hits (filled)", "measured (filled)", "model (filled)", "error",
                             "hits (path)", "measured (path)", "model (path)", "error"});
            for (const SceneRow& r : rows) {
                const TechniqueRow& tr = r.*pick;
                t.addRow({r.scene + (r.animated ? " (animated)" : ""), cellNumber(100.0 * r.coverage, 0) + " %",
                          cellNumber(100.0 * r.stillShare, 0) + " %",
                          cellNumber(freeCacheSpeedup(tr.stillParts), 2) + "×",
                          cellNumber(100.0 * tr.stillParts.hitRate, 0) + " %", speedupCell(tr.stillMeasured),
                          cellNumber(tr.stillPredicted, 2) + "×",
                          errorCell(relativeError(tr.stillPredicted, tr.stillMeasured.speedup)),
                          cellNumber(100.0 * tr.pathParts.hitRate, 0) + " %", speedupCell(tr.pathMeasured),
                          cellNumber(tr.pathPredicted, 2) + "×",
                          errorCell(relativeError(tr.pathPredicted, tr.pathMeasured.speedup))});
            }
            md += t.toMarkdown() + "\n";
            double worst = 0.0;
            int pays = 0;
            for (const SceneRow& r : rows) {
                const TechniqueRow& tr = r.*pick;
                for (double e : {relativeError(tr.stillPredicted, tr.stillMeasured.speedup),
                                 relativeError(tr.pathPredicted, tr.pathMeasured.speedup)})
                    if (std::isfinite(e)) worst = std::max(worst, std::fabs(e));
                if (tr.stillMeasured.known() ? tr.stillMeasured.low > 1.0 : tr.stillMeasured.speedup > 1.0) ++pays;
            }
            out.headlines.push_back("where-caching-pays: " + std::string(label) + " with filled caches faster than "
                                    "uncached on " + std::to_string(pays) + " of " + std::to_string(rows.size()) +
                                    " scenes; the model within " + cellNumber(100.0 * worst, 0) +
                                    " % of every measured speed-up");
        }
        md += "### CCT under `--cache-policy auto` (the CLI's default)\n\n";
        MarkdownTable t({"scene", "filled: always", "filled: auto", "path: always", "path: auto",
                         "cube-frames sampling / stood aside (path)"});
        int notSlower = 0;
        double lowest = std::numeric_limits<double>::infinity();
        for (const SceneRow& r : rows) {
            t.addRow({r.scene + (r.animated ? " (animated)" : ""), speedupCell(r.cct.stillMeasured),
                      speedupCell(r.autoStill), speedupCell(r.cct.pathMeasured), speedupCell(r.autoPath),
                      cellNumber(100.0 * r.autoSamplingShare, 0) + " % / " +
                          cellNumber(100.0 * r.autoBypassedShare, 0) + " %"});
            // Not slower: the interval reaches 1 or lies above it.
            if (r.autoPath.known() ? r.autoPath.high >= 1.0 : r.autoPath.speedup >= 1.0) ++notSlower;
            if (std::isfinite(r.autoPath.speedup)) lowest = std::min(lowest, r.autoPath.speedup);
        }
        md += t.toMarkdown() + "\n";
        out.headlines.push_back("where-caching-pays: CCT auto along the path not measurably slower than uncached on " +
                                std::to_string(notSlower) + " of " + std::to_string(rows.size()) +
                                " scenes; lowest " + cellNumber(lowest, 2) + "×");
        return md;
    }

    static SvgPlot plot(const std::vector<SceneRow>& rows) {
        SvgPlot p;
        p.title = "Speed-up over uncached against the cacheable share, caches filled";
        p.xLabel = "cacheable share of the uncached frame (ideal cache's saving)";
        p.yLabel = "speed-up (×)";
        p.referenceY = 1.0;
        PlotSeries cct{"CCT measured", {}}, cctModel{"CCT model", {}}, cdct{"CDCT measured", {}},
            cdctModel{"CDCT model", {}};
        for (PlotSeries* s : {&cct, &cctModel, &cdct, &cdctModel}) s->line = false;
        cctModel.dashed = cdctModel.dashed = true;
        for (const SceneRow& r : rows) {
            cct.points.push_back({r.stillShare, r.cct.stillMeasured.speedup});
            cctModel.points.push_back({r.stillShare, r.cct.stillPredicted});
            cdct.points.push_back({r.stillShare, r.cdct.stillMeasured.speedup});
            cdctModel.points.push_back({r.stillShare, r.cdct.stillPredicted});
        }
        // The bound every cache stays under, drawn across the shares measured.
        PlotSeries bound{"free cache: 1 / (1 − share)", {}};
        bound.dashed = true;
        double widest = 0.0;
        for (const SceneRow& r : rows)
            if (std::isfinite(r.stillShare)) widest = std::max(widest, std::min(r.stillShare, 0.9));
        for (int i = 0; i <= 20; ++i) {
            const double share = widest * i / 20.0;
            bound.points.push_back({share, 1.0 / (1.0 - share)});
        }
        p.series = {cct, cctModel, cdct, cdctModel, bound};
        return p;
    }
};

}  // namespace

std::unique_ptr<Experiment> makeWhereCachingPaysExperiment() { return std::make_unique<WhereCachingPaysExperiment>(); }

}  // namespace raycache
