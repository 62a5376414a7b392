#include "bench/TimingTableExperiment.h"

#include <chrono>
#include <cmath>

#include "bench/AdaptiveStopping.h"
#include "bench/InterleavedRuns.h"
#include "bench/MachineLoad.h"
#include "bench/MarkdownTable.h"
#include "bench/ResultsJson.h"
#include "bench/SpeedupInterval.h"
#include "bench/SvgPlot.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/SampleSummary.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"
#include "trace/TraceScene.h"

namespace raycache {

namespace {

double megapixels(const TimingSize& s) {
    return static_cast<double>(s.width) * s.height / 1e6;
}

std::string techniqueName(const std::optional<CacheTechnique>& t) {
    return t ? cacheTechniqueName(*t) : "scene materials";
}

// What one variant measured on one scene.
struct VariantResult {
    const TimingVariant* variant = nullptr;
    VariantTimes still;
    std::optional<FrameCacheStats> stillCache;       // last timed still frame
    VariantTimes moving;                             // one entry per whole-path run (ms per frame, averaged)
    std::vector<std::vector<double>> movingFrameMs;  // per round, every frame of the path
    std::optional<FrameCacheStats> movingLastCache;  // last frame of the last path run
    SpeedupInterval stillSpeedup;                    // over the baseline, still camera
    SpeedupInterval movingSpeedup;                   // over the baseline, camera path
    bool measured() const { return variant->unavailable.empty(); }
};

nlohmann::json lastFrameCacheJson(const std::optional<FrameCacheStats>& c) {
    if (!c) return nullptr;
    const double lookups = static_cast<double>(c->lookups());
    return {{"lookups", c->lookups()},
            {"hits", c->hits()},
            {"hit_percent", finiteOrNull(lookups > 0 ? 100.0 * static_cast<double>(c->hits()) / lookups : 0.0)},
            {"invalid_percent_before", c->invalidPercentBefore()},
            {"bytes", c->bytes()}};
}

double hitPercent(const std::optional<FrameCacheStats>& c) {
    if (!c || c->lookups() == 0) return std::nan("");
    return 100.0 * static_cast<double>(c->hits()) / static_cast<double>(c->lookups());
}

// A plotted speed-up with its interval as the whisker.
PlotPoint intervalPoint(double x, const SpeedupInterval& s) {
    PlotPoint p{x, s.speedup, std::nullopt, std::nullopt};
    if (s.known()) {
        p.low = s.low;
        p.high = s.high;
    }
    return p;
}

AdaptiveSettings adaptiveSettings(const TimingSize& s) {
    AdaptiveSettings a;
    a.minRounds = s.timedFrames;
    a.maxRounds = std::max(s.timedFrames, s.maxTimedFrames);
    a.timeCapSeconds = s.timeCapSeconds;
    return a;
}

// Moving camera: frame f of round r of the variant paired with the same frame
// of the baseline (same camera), the mean over the path per variant.
SpeedupInterval movingInterval(const VariantResult& baseline, const VariantResult& variant) {
    std::vector<double> b, v;
    for (std::size_t r = 0; r < std::min(baseline.movingFrameMs.size(), variant.movingFrameMs.size()); ++r) {
        const std::size_t n = std::min(baseline.movingFrameMs[r].size(), variant.movingFrameMs[r].size());
        b.insert(b.end(), baseline.movingFrameMs[r].begin(), baseline.movingFrameMs[r].begin() + n);
        v.insert(v.end(), variant.movingFrameMs[r].begin(), variant.movingFrameMs[r].begin() + n);
    }
    BootstrapSettings settings;
    settings.statistic = TimeStatistic::Mean;
    return bootstrapSpeedup(b, v, settings);
}

// One scene's timings: every variant's results and how the still-camera run stopped.
struct SceneTimings {
    std::vector<VariantResult> variants;
    AdaptiveRun stillRun;
};

// How busy the machine was while the table ran: read when made and again by stop().
struct MachineWatch {
    LoadAverage loadBefore = currentLoadAverage();
    CpuSample cpuBefore = currentCpuSample();
    LoadAverage loadAfter;
    double othersShare = -1.0;  // the share of CPU time other processes took; < 0: unknown
    std::string busyWarning;    // a caveat when they took much of it, else empty

    void stop() {
        const CpuSample cpuAfter = currentCpuSample();
        loadAfter = currentLoadAverage();
        othersShare = othersCpuShare(cpuBefore, cpuAfter);
        busyWarning = busyMachineWarning(othersShare, loadBefore, loadAfter, cpuAfter.cpus);
    }
    std::string markdown() const {
        return "Other processes used " + formatOthersShare(othersShare) +
               " of the machine's CPU time while this table ran. " + "Load average (1, 5, 15 min): " +
               loadBefore.toString() + " before, " + loadAfter.toString() +
               " after (it includes the bench's own earlier work).\n\n";
    }
};

std::size_t sceneCountFor(const TimingTableSpec& spec, const TimingSize& size) {
    return size.scenes > 0 ? std::min<std::size_t>(spec.scenes.size(), static_cast<std::size_t>(size.scenes))
                           : spec.scenes.size();
}

Scene loadTableScene(const TimingTableSpec& spec, const TimingScene& ts) {
    std::optional<Scene> maybeScene = makeBuiltinScene(ts.scene);
    if (!maybeScene) throw RuntimeError("built-in scene " + ts.scene + " is missing");
    Scene scene = std::move(*maybeScene);
    if (spec.adjustScene) spec.adjustScene(scene);
    return scene;
}

RenderSettings variantSettings(const TimingTableSpec& spec, const TimingVariant& v, const TimingSize& size,
                               int threads) {
    RenderSettings s;
    s.width = size.width;
    s.height = size.height;
    s.threads = threads;
    s.cache.techniqueOverride = v.technique;
    // The documents' protocol (Tables 5.1-5.3): every cube caches every
    // frame, whatever the cache policy would decide.
    s.cache.policy = CachePolicyMode::Always;
    s.cache.resolutionOverride = size.cacheResolution;
    if (v.cdct) {
        s.cache.cdctStepOverride = v.cdct->step;
        s.cache.cdctEpsilonOverride = v.cdct->epsilon;
        s.cache.cdctMaxDepthOverride = v.cdct->maxDepth;
    }
    if (spec.configure) spec.configure(s);
    return s;
}

// One session per variant this build can run (null for the others); each
// result learns its variant.
std::vector<std::unique_ptr<RenderSession>> makeVariantSessions(const TimingTableSpec& spec, const TimingSize& size,
                                                                const Scene& scene, const TraceScene& tracer,
                                                                ExperimentContext& context,
                                                                std::vector<VariantResult>& results) {
    std::vector<std::unique_ptr<RenderSession>> sessions(spec.variants.size());
    for (std::size_t vi = 0; vi < spec.variants.size(); ++vi) {
        const TimingVariant& v = spec.variants[vi];
        results[vi].variant = &v;
        if (!v.unavailable.empty()) continue;
        sessions[vi] = std::make_unique<RenderSession>(
            scene, variantSettings(spec, v, size, context.settings.threads), tracer, context.parallel);
    }
    return sessions;
}

// (a) Still camera: warm-up frames fill the caches, then timed frames, variants in turn.
AdaptiveRun timeStillCamera(const TimingTableSpec& spec, const TimingSize& size, const Scene& scene,
                            std::vector<std::unique_ptr<RenderSession>>& sessions,
                            const std::vector<std::size_t>& measured, ExperimentContext& context,
                            std::vector<VariantResult>& results, Image& film) {
    std::vector<Variant> still;
    for (const std::size_t vi : measured) {
        const double work = spec.variants[vi].costWeight * megapixels(size);
        still.push_back({spec.variants[vi].label,
                         [&, vi] {
                             const FrameStats stats = sessions[vi]->render(scene.camera, film);
                             results[vi].stillCache = stats.cache;
                             return stats.rays.total();
                         },
                         {},
                         [&, work] { context.progress.advance(work); }});
    }
    const AdaptiveRun stillRun = runInterleavedAdaptive(still, size.warmupFrames, adaptiveSettings(size));
    for (std::size_t k = 0; k < measured.size(); ++k) results[measured[k]].still = stillRun.times[k];
    return stillRun;
}

// (b) Moving camera from empty caches: the whole path per run, caches filling as they go.
void timeMovingCamera(const TimingTableSpec& spec, const TimingSize& size, const Scene& scene,
                      std::vector<std::unique_ptr<RenderSession>>& sessions, const std::vector<std::size_t>& measured,
                      ExperimentContext& context, std::vector<VariantResult>& results, Image& film) {
    std::vector<Variant> moving;
    for (const std::size_t vi : measured) {
        const double work = spec.variants[vi].costWeight * megapixels(size) * size.movingFrames;
        moving.push_back({spec.variants[vi].label,
                          [&, vi] {
                              std::uint64_t rays = 0;
                              std::vector<double> frameMs;
                              for (int f = 0; f < size.movingFrames; ++f) {
                                  const Camera camera = scene.cameraPath.cameraAt(scene.camera, f);
                                  const auto start = std::chrono::steady_clock::now();
                                  const FrameStats stats = sessions[vi]->render(camera, film);
                                  frameMs.push_back(std::chrono::duration<double, std::milli>(
                                                        std::chrono::steady_clock::now() - start)
                                                        .count());
                                  rays += stats.rays.total();
                                  results[vi].movingLastCache = stats.cache;
                              }
                              results[vi].movingFrameMs.push_back(std::move(frameMs));
                              return rays;
                          },
                          [&, vi] { sessions[vi]->cache().clear(); }, [&, work] { context.progress.advance(work); }});
    }
    const std::vector<VariantTimes> movingTimes = runInterleaved(moving, 0, size.movingRounds);
    for (std::size_t k = 0; k < measured.size(); ++k) {
        VariantTimes perFrame = movingTimes[k];
        for (double& ms : perFrame.milliseconds) ms /= size.movingFrames;
        results[measured[k]].moving = perFrame;
    }
}

// Every variant's speed-up over the baseline (variants[0]), still and moving.
void computeSpeedups(std::vector<VariantResult>& results) {
    for (VariantResult& r : results) {
        if (!r.measured() || !results[0].measured()) continue;
        r.stillSpeedup = bootstrapSpeedup(results[0].still.milliseconds, r.still.milliseconds);
        if (!r.movingFrameMs.empty()) r.movingSpeedup = movingInterval(results[0], r);
    }
}

// All variants of one scene: still camera, then (if the size asks) the moving camera.
SceneTimings timeScene(const TimingTableSpec& spec, const TimingSize& size, const TimingScene& ts,
                       ExperimentContext& context) {
    context.progress.step(spec.name + ": " + ts.scene);
    const Scene scene = loadTableScene(spec, ts);
    const TraceScene tracer(scene);
    SceneTimings timings;
    timings.variants.resize(spec.variants.size());
    std::vector<VariantResult>& results = timings.variants;
    std::vector<std::unique_ptr<RenderSession>> sessions =
        makeVariantSessions(spec, size, scene, tracer, context, results);
    std::vector<std::size_t> measured;
    for (std::size_t vi = 0; vi < spec.variants.size(); ++vi)
        if (results[vi].measured()) measured.push_back(vi);
    Image film;
    timings.stillRun = timeStillCamera(spec, size, scene, sessions, measured, context, results, film);
    if (size.movingFrames > 0 && size.movingRounds > 0)
        timeMovingCamera(spec, size, scene, sessions, measured, context, results, film);
    computeSpeedups(results);
    return timings;
}

nlohmann::json variantJson(const TimingTableSpec& spec, const TimingScene& ts, const VariantResult& r) {
    const std::string& baselineKey = spec.variants.front().key;
    nlohmann::json v = {{"label", r.variant->label},
                        {"technique", techniqueName(r.variant->technique)},
                        {"documents_fps",
                         finiteOrNull(spec.documents.value(ts.label, r.variant->key).value_or(std::nan("")))}};
    if (r.variant->cdct)
        v["cdct"] = {{"step", r.variant->cdct->step},
                     {"epsilon", r.variant->cdct->epsilon},
                     {"max_depth", r.variant->cdct->maxDepth}};
    if (!r.measured()) {
        v["available"] = false;
        v["unavailable_reason"] = r.variant->unavailable;
        return v;
    }
    v["available"] = true;
    v["still"] = toJson(r.still);
    v["still"]["speedup_vs_" + baselineKey] = toJson(r.stillSpeedup);
    v["still"]["cache_last_frame"] = lastFrameCacheJson(r.stillCache);
    if (!r.movingFrameMs.empty()) {
        v["moving"] = toJson(r.moving);
        v["moving"]["frame_ms_per_round"] = r.movingFrameMs;
        v["moving"]["speedup_vs_" + baselineKey] = toJson(r.movingSpeedup);
        v["moving"]["cache_last_frame"] = lastFrameCacheJson(r.movingLastCache);
    }
    return v;
}

nlohmann::json sceneRowJson(const TimingTableSpec& spec, const TimingScene& ts, const SceneTimings& timings) {
    nlohmann::json variantsJson = nlohmann::json::object();
    for (const VariantResult& r : timings.variants) variantsJson[r.variant->key] = variantJson(spec, ts, r);
    return {{"scene", ts.scene},
            {"label", ts.label},
            {"still_timed_rounds", timings.stillRun.rounds},
            {"still_timed_seconds", timings.stillRun.seconds},
            {"still_stop_reason", toString(timings.stillRun.reason)},
            {"variants", variantsJson}};
}

// What was measured and how, above the table.
std::string protocolMarkdown(const TimingTableSpec& spec, const TimingSize& size, BenchSize benchSize,
                             const std::vector<SceneTimings>& table) {
    std::string md = spec.description + "\n\n";
    md += "Size `" + toString(benchSize) + "`: " + std::to_string(size.width) + "x" + std::to_string(size.height) +
          ", " + std::to_string(size.cacheResolution) + "² cache faces, " + std::to_string(size.warmupFrames) +
          " warm-up + " + std::to_string(size.timedFrames) +
          (size.maxTimedFrames > size.timedFrames
               ? " or more timed frames per variant (still camera, variants interleaved, repeated until every "
                 "speed-up's 95 % interval is within ±5 %, at most " +
                     std::to_string(size.maxTimedFrames) + " rounds and " + cellNumber(size.timeCapSeconds, 1) +
                     " s per scene)"
               : " timed frames per variant (still camera, variants interleaved)");
    if (size.movingFrames > 0)
        md += "; moving camera: the scene's path, " + std::to_string(size.movingFrames) +
              " frames from empty caches, " + std::to_string(size.movingRounds) + " run(s) per variant";
    md +=
        ". Times are ms per frame, median (min–max); speed-up = uncached median / variant median, with its 95 % "
        "confidence interval in brackets (paired bootstrap over the interleaved rounds, 2000 resamples, fixed seed; "
        "moving camera: over the path's frames, mean times). Where the interval contains 1 the table says *no "
        "measurable difference*. The documents' figures are GPU frame rates: compare speed-ups, not frame rates.\n\n";
    md += "Timed rounds (still camera): ";
    for (std::size_t si = 0; si < table.size(); ++si) {
        const AdaptiveRun& stop = table[si].stillRun;
        md += (si ? "; " : "") + spec.rowHeader + " = " + spec.scenes[si].label + ": " + std::to_string(stop.rounds) +
              " (" + toString(stop.reason) + ", " + cellNumber(stop.seconds, 1) + " s)";
    }
    md += ".\n\n";
    return md;
}

SvgPlot frameTimePlot(const TimingTableSpec& spec, const std::vector<SceneTimings>& table) {
    SvgPlot timePlot;
    timePlot.title = spec.name + ": ms per frame, still camera, caches filled (median, min–max)";
    timePlot.yLabel = "ms per frame";
    for (std::size_t si = 0; si < table.size(); ++si) timePlot.categories.push_back(spec.scenes[si].label);
    timePlot.xLabel = spec.rowHeader;
    for (std::size_t vi = 0; vi < spec.variants.size(); ++vi) {
        if (!spec.variants[vi].unavailable.empty()) continue;
        PlotSeries series{spec.variants[vi].label, {}};
        for (std::size_t si = 0; si < table.size(); ++si) {
            const SampleSummary s = summarize(table[si].variants[vi].still.milliseconds);
            series.points.push_back({static_cast<double>(si), s.median, s.min, s.max});
        }
        timePlot.series.push_back(std::move(series));
    }
    return timePlot;
}

// The one-line finding of a table whose rows are scenes: variants[1]'s
// speed-up at the first and last scene, beside the documents'.
std::string sceneRowsHeadline(const TimingTableSpec& spec, const std::vector<SceneTimings>& table) {
    const TimingVariant& compared = spec.variants.at(1);
    const SpeedupInterval& first = table.front().variants[1].stillSpeedup;
    const SpeedupInterval& last = table.back().variants[1].stillSpeedup;
    std::string alike;
    for (std::size_t si = 0; si < table.size(); ++si)
        if (table[si].variants[1].stillSpeedup.containsOne())
            alike += (alike.empty() ? "" : ", ") + spec.scenes[si].label;
    return spec.name + ": " + compared.label + " speed-up " + describeSpeedup(first) + " at " + spec.rowHeader +
           " = " + spec.scenes.front().label + " to " + describeSpeedup(last) + " at " + spec.rowHeader + " = " +
           spec.scenes[table.size() - 1].label + ", caches filled" +
           (alike.empty() ? "" : "; no measurable difference at " + spec.rowHeader + " = " + alike) + "; documents " +
           cellNumber(
               spec.documents.value(spec.scenes.front().label, spec.documentsSpeedupColumn).value_or(std::nan("")),
               2) +
           "× to " +
           cellNumber(spec.documents.value(spec.scenes[table.size() - 1].label, spec.documentsSpeedupColumn)
                          .value_or(std::nan("")),
                      2) +
           "×";
}

// Rows = scenes, the baseline and variants[1] side by side (Tables 5.1, 5.2):
// the table goes to `md`, the speed-ups to `speedPlot`, the finding to `out`.
void addSceneRows(const TimingTableSpec& spec, const TimingSize& size, const std::vector<SceneTimings>& table,
                  const std::vector<std::string>& categories, std::string& md, SvgPlot& speedPlot,
                  ExperimentOutput& out) {
    const TimingVariant& baseline = spec.variants.front();
    const TimingVariant& compared = spec.variants.at(1);
    const bool hasMoving = size.movingFrames > 0 && size.movingRounds > 0;
    std::vector<std::string> headers{
        spec.rowHeader,        "documents: " + baseline.label + " fps", "documents: " + compared.label + " fps",
        "documents: speed-up", "raycache: " + baseline.label + " ms",   "raycache: " + compared.label + " ms",
        "raycache: speed-up"};
    if (hasMoving) {
        headers.push_back("moving camera: speed-up");
        headers.push_back(compared.label + " hit rate, last moving frame");
    }
    MarkdownTable t(headers);
    const std::string& source = spec.documents.source;
    PlotSeries ours{"raycache, caches filled", {}}, oursMoving{"raycache, moving camera", {}},
        documents{"documents (" + source.substr(source.rfind(", ") + 2) + ")", {}};
    documents.dashed = true;
    for (std::size_t si = 0; si < table.size(); ++si) {
        const auto& r = table[si].variants;
        const std::string& label = spec.scenes[si].label;
        const double docBase = spec.documents.value(label, baseline.key).value_or(std::nan(""));
        const double docComp = spec.documents.value(label, compared.key).value_or(std::nan(""));
        const double docSpeed = spec.documentsSpeedupColumn.empty()
                                    ? docComp / docBase
                                    : spec.documents.value(label, spec.documentsSpeedupColumn).value_or(std::nan(""));
        const SampleSummary b = summarize(r[0].still.milliseconds), c = summarize(r[1].still.milliseconds);
        const SpeedupInterval& speed = r[1].stillSpeedup;
        std::vector<std::string> row{label,
                                     cellNumber(docBase, 1),
                                     cellNumber(docComp, 1),
                                     cellNumber(docSpeed, 2) + (std::isfinite(docSpeed) ? "×" : ""),
                                     cellRange(b, 1),
                                     cellRange(c, 1),
                                     speedupCell(speed)};
        SpeedupInterval movingSpeed{std::nan(""), std::nan(""), std::nan(""), 0};
        if (hasMoving) {
            movingSpeed = r[1].movingSpeedup;
            row.push_back(speedupCell(movingSpeed));
            row.push_back(cellNumber(hitPercent(r[1].movingLastCache), 1) + "%");
        }
        t.addRow(row);
        ours.points.push_back(intervalPoint(static_cast<double>(si), speed));
        oursMoving.points.push_back(intervalPoint(static_cast<double>(si), movingSpeed));
        documents.points.push_back({static_cast<double>(si), docSpeed});
    }
    md += t.toMarkdown();
    speedPlot.title = spec.name + ": speed-up of " + compared.label + " over " + baseline.label +
                      " (whiskers: 95 % confidence interval)";
    speedPlot.xLabel = spec.rowHeader;
    speedPlot.yLabel = "speed-up (×)";
    speedPlot.categories = categories;
    speedPlot.series.push_back(std::move(ours));
    if (hasMoving) speedPlot.series.push_back(std::move(oursMoving));
    speedPlot.series.push_back(std::move(documents));
    if (!table.empty()) out.headlines.push_back(sceneRowsHeadline(spec, table));
}

// Rows = variants, a column group per scene (Table 5.3): the table goes to
// `md`, the frame-rate ratios to `speedPlot`, a finding per variant and scene to `out`.
void addVariantRows(const TimingTableSpec& spec, const std::vector<SceneTimings>& table, std::string& md,
                    SvgPlot& speedPlot, ExperimentOutput& out) {
    const TimingVariant& baseline = spec.variants.front();
    std::vector<std::string> headers{"variant"};
    for (std::size_t si = 0; si < table.size(); ++si) {
        const std::string& label = spec.scenes[si].label;
        headers.push_back(label + ": documents fps");
        headers.push_back(label + ": documents × " + baseline.label);
        headers.push_back(label + ": raycache ms");
        headers.push_back(label + ": raycache × " + baseline.label);
        headers.push_back(label + ": hit rate");
    }
    MarkdownTable t(headers);
    speedPlot.title = spec.name + ": frame rate relative to " + baseline.label +
                      " (higher is faster; whiskers: 95 % confidence interval)";
    speedPlot.yLabel = "× " + baseline.label + " frame rate";
    speedPlot.bars = true;
    speedPlot.height = 480;
    for (const TimingVariant& v : spec.variants) speedPlot.categories.push_back(v.label);
    std::vector<PlotSeries> oursSeries(table.size()), docsSeries(table.size());
    for (std::size_t si = 0; si < table.size(); ++si) {
        oursSeries[si].name = spec.scenes[si].label + ", raycache";
        docsSeries[si].name = spec.scenes[si].label + ", documents";
        docsSeries[si].dashed = true;
    }
    for (std::size_t vi = 0; vi < spec.variants.size(); ++vi) {
        const TimingVariant& v = spec.variants[vi];
        std::vector<std::string> row{v.label};
        for (std::size_t si = 0; si < table.size(); ++si) {
            const VariantResult& result = table[si].variants[vi];
            const std::string& label = spec.scenes[si].label;
            const double docFps = spec.documents.value(label, v.key).value_or(std::nan(""));
            const double docBase = spec.documents.value(label, baseline.key).value_or(std::nan(""));
            row.push_back(cellNumber(docFps, 1));
            row.push_back(std::isfinite(docFps / docBase) ? cellNumber(docFps / docBase, 2) + "×" : "–");
            docsSeries[si].points.push_back({static_cast<double>(vi), docFps / docBase});
            if (!result.measured()) {
                row.push_back("not available in this build");
                row.push_back("–");
                row.push_back("–");
                oursSeries[si].points.push_back({static_cast<double>(vi), std::nan("")});
                continue;
            }
            const SampleSummary s = summarize(result.still.milliseconds);
            const SpeedupInterval& rel = result.stillSpeedup;
            row.push_back(cellRange(s, 1));
            row.push_back(vi == 0 ? "1.00×" : speedupCell(rel));
            row.push_back(result.stillCache ? cellNumber(hitPercent(result.stillCache), 1) + "%" : "–");
            oursSeries[si].points.push_back(intervalPoint(static_cast<double>(vi), rel));
            if (vi > 0)
                out.headlines.push_back(spec.name + " " + spec.scenes[si].label + ": " + v.label + " vs " +
                                        baseline.label + ": " + describeSpeedup(rel) + ", documents " +
                                        (std::isfinite(docFps / docBase) ? cellNumber(docFps / docBase, 2) + "×" : "–") +
                                        ", cache hit rate " + cellNumber(hitPercent(result.stillCache), 1) + "%");
        }
        t.addRow(row);
    }
    md += t.toMarkdown();
    for (std::size_t si = 0; si < table.size(); ++si) {
        speedPlot.series.push_back(std::move(oursSeries[si]));
        speedPlot.series.push_back(std::move(docsSeries[si]));
    }
    speedPlot.referenceY = 1.0;
}

nlohmann::json tableSettingsJson(const TimingTableSpec& spec, const TimingSize& size) {
    nlohmann::json variantsSpec = nlohmann::json::array();
    for (const TimingVariant& v : spec.variants)
        variantsSpec.push_back({{"key", v.key},
                                {"label", v.label},
                                {"technique", techniqueName(v.technique)},
                                {"available", v.unavailable.empty()}});
    return {{"width", size.width},
            {"height", size.height},
            {"cache_resolution", size.cacheResolution},
            {"cache_policy", "always"},  // the documents' protocol, whatever --cache-policy says
            {"warmup_frames", size.warmupFrames},
            {"timed_frames", size.timedFrames},
            {"max_timed_frames", std::max(size.timedFrames, size.maxTimedFrames)},
            {"time_cap_seconds_per_scene", size.timeCapSeconds},
            {"target_ci_half_width", AdaptiveSettings{}.targetHalfWidth},
            {"bootstrap",
             {{"resamples", BootstrapSettings{}.resamples},
              {"seed", BootstrapSettings{}.seed},
              {"confidence", BootstrapSettings{}.confidence}}},
            {"moving_frames", size.movingFrames},
            {"moving_rounds", size.movingRounds},
            {"max_depth", RenderSettings{}.maxDepth},
            {"pipeline", spec.pipeline},
            {"variants", variantsSpec}};
}

}  // namespace

const TimingSize& TimingTableExperiment::sizeFor(BenchSize size) const {
    return size == BenchSize::Full ? spec_.full : size == BenchSize::Quick ? spec_.quick : spec_.tiny;
}

double TimingTableExperiment::estimatedWork(const BenchSettings& settings) const {
    const TimingSize& s = sizeFor(settings.size);
    const std::size_t scenes = sceneCountFor(spec_, s);
    double perScene = 0.0;
    for (const TimingVariant& v : spec_.variants) {
        if (!v.unavailable.empty()) continue;
        perScene += v.costWeight * megapixels(s) *
                    (s.warmupFrames + s.timedFrames + static_cast<double>(s.movingFrames) * s.movingRounds);
    }
    return perScene * static_cast<double>(scenes);
}

ExperimentOutput TimingTableExperiment::run(ExperimentContext& context) const {
    const TimingSize& size = sizeFor(context.settings.size);
    MachineWatch watch;
    std::vector<SceneTimings> table;
    nlohmann::json rowsJson = nlohmann::json::array();
    for (std::size_t si = 0; si < sceneCountFor(spec_, size); ++si) {
        table.push_back(timeScene(spec_, size, spec_.scenes[si], context));
        rowsJson.push_back(sceneRowJson(spec_, spec_.scenes[si], table.back()));
    }

    ExperimentOutput out;
    out.name = spec_.name;
    out.title = spec_.title;
    out.caveats = spec_.caveats;
    std::string md = protocolMarkdown(spec_, size, context.settings.size, table);
    const SvgPlot timePlot = frameTimePlot(spec_, table);
    SvgPlot speedPlot;
    speedPlot.referenceY = 1.0;
    if (spec_.rowsAreScenes) addSceneRows(spec_, size, table, timePlot.categories, md, speedPlot, out);
    else addVariantRows(spec_, table, md, speedPlot, out);
    for (const TimingVariant& v : spec_.variants)
        if (!v.unavailable.empty()) out.caveats.push_back(v.label + ": " + v.unavailable);
    watch.stop();
    md += watch.markdown();
    if (!watch.busyWarning.empty()) out.caveats.push_back(watch.busyWarning);

    writeSvgPlot(speedPlot, (context.dir / "speedup.svg").string());
    writeSvgPlot(timePlot, (context.dir / "frame-times.svg").string());
    out.plots = {"speedup.svg", "frame-times.svg"};
    out.markdown = md;

    // null where /proc/stat could not be read
    const nlohmann::json othersJson = watch.othersShare >= 0.0 ? nlohmann::json(watch.othersShare) : nlohmann::json();
    const nlohmann::json root = {
        {"experiment", spec_.name},
        {"title", spec_.title},
        {"size", toString(context.settings.size)},
        {"settings", tableSettingsJson(spec_, size)},
        {"environment", toJson(context.environment)},
        {"documents", toJson(spec_.documents)},
        {"load_average", {{"before", watch.loadBefore.toString()}, {"after", watch.loadAfter.toString()}}},
        {"others_cpu_share", othersJson},
        {"caveats", out.caveats},
        {"rows", rowsJson}};
    writeJsonFile(context.dir / "results.json", root);
    writeTextFileAtomically(context.dir / "results.md", experimentMarkdown(out));
    return out;
}

void setSquareTableSizes(TimingTableSpec& spec) {
    spec.full = {.width = 1024,
                 .height = 1024,
                 .warmupFrames = 2,
                 .timedFrames = 7,
                 .movingFrames = 10,
                 .movingRounds = 3,
                 .maxTimedFrames = 60,
                 .timeCapSeconds = 20.0};
    spec.quick = {.width = 512,
                  .height = 512,
                  .warmupFrames = 1,
                  .timedFrames = 4,
                  .movingFrames = 10,
                  .movingRounds = 1,
                  .maxTimedFrames = 40,
                  .timeCapSeconds = 1.5};
    spec.tiny = {.width = 32,
                 .height = 32,
                 .warmupFrames = 1,
                 .timedFrames = 2,
                 .movingFrames = 2,
                 .movingRounds = 1,
                 .scenes = 2,
                 .cacheResolution = 32};
}

}  // namespace raycache
