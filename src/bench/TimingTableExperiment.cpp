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

}  // namespace

const TimingSize& TimingTableExperiment::sizeFor(BenchSize size) const {
    return size == BenchSize::Full ? spec_.full : size == BenchSize::Quick ? spec_.quick : spec_.tiny;
}

double TimingTableExperiment::estimatedWork(const BenchSettings& settings) const {
    const TimingSize& s = sizeFor(settings.size);
    const std::size_t scenes = s.scenes > 0
                                   ? std::min<std::size_t>(spec_.scenes.size(), static_cast<std::size_t>(s.scenes))
                                   : spec_.scenes.size();
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
    const std::size_t sceneCount =
        size.scenes > 0 ? std::min<std::size_t>(spec_.scenes.size(), static_cast<std::size_t>(size.scenes))
                        : spec_.scenes.size();
    const TimingVariant& baseline = spec_.variants.front();

    nlohmann::json rowsJson = nlohmann::json::array();
    std::vector<std::vector<VariantResult>> table;  // [scene][variant]
    std::vector<AdaptiveRun> stops;                 // per scene: rounds, time, why the still run stopped
    const LoadAverage loadBefore = currentLoadAverage();
    const CpuSample cpuBefore = currentCpuSample();

    for (std::size_t si = 0; si < sceneCount; ++si) {
        const TimingScene& ts = spec_.scenes[si];
        context.progress.step(spec_.name + ": " + ts.scene);
        std::optional<Scene> maybeScene = makeBuiltinScene(ts.scene);
        if (!maybeScene) throw RuntimeError("built-in scene " + ts.scene + " is missing");
        Scene scene = std::move(*maybeScene);
        if (spec_.adjustScene) spec_.adjustScene(scene);
        const TraceScene tracer(scene);

        std::vector<VariantResult> results(spec_.variants.size());
        std::vector<RenderSettings> settings(spec_.variants.size());
        std::vector<std::unique_ptr<RenderSession>> renderers(spec_.variants.size());
        for (std::size_t vi = 0; vi < spec_.variants.size(); ++vi) {
            const TimingVariant& v = spec_.variants[vi];
            results[vi].variant = &v;
            if (!v.unavailable.empty()) continue;
            RenderSettings& s = settings[vi];
            s.width = size.width;
            s.height = size.height;
            s.threads = context.settings.threads;
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
            if (spec_.configure) spec_.configure(s);
            renderers[vi] = std::make_unique<RenderSession>(scene, s, tracer, context.parallel);
        }

        // (a) Still camera: warm-up frames fill the caches, then timed frames, variants in turn.
        Image film;
        std::vector<Variant> still, moving;
        std::vector<std::size_t> measuredIndex;
        for (std::size_t vi = 0; vi < spec_.variants.size(); ++vi) {
            if (!results[vi].measured()) continue;
            measuredIndex.push_back(vi);
            const double work = spec_.variants[vi].costWeight * megapixels(size);
            still.push_back({spec_.variants[vi].label,
                             [&, vi] {
                                 const FrameStats stats = renderers[vi]->render(scene.camera, film);
                                 results[vi].stillCache = stats.cache;
                                 return stats.rays.total();
                             },
                             {},
                             [&, work] { context.progress.advance(work); }});
        }
        const AdaptiveRun stillRun = runInterleavedAdaptive(still, size.warmupFrames, adaptiveSettings(size));
        for (std::size_t k = 0; k < measuredIndex.size(); ++k) results[measuredIndex[k]].still = stillRun.times[k];
        stops.push_back(stillRun);

        // (b) Moving camera from empty caches: the whole path per run, caches filling as they go.
        if (size.movingFrames > 0 && size.movingRounds > 0) {
            for (std::size_t vi : measuredIndex) {
                const double work = spec_.variants[vi].costWeight * megapixels(size) * size.movingFrames;
                moving.push_back({spec_.variants[vi].label,
                                  [&, vi] {
                                      std::uint64_t rays = 0;
                                      std::vector<double> frameMs;
                                      for (int f = 0; f < size.movingFrames; ++f) {
                                          const Camera camera = scene.cameraPath.cameraAt(scene.camera, f);
                                          const auto start = std::chrono::steady_clock::now();
                                          const FrameStats stats = renderers[vi]->render(camera, film);
                                          frameMs.push_back(std::chrono::duration<double, std::milli>(
                                                                std::chrono::steady_clock::now() - start)
                                                                .count());
                                          rays += stats.rays.total();
                                          results[vi].movingLastCache = stats.cache;
                                      }
                                      results[vi].movingFrameMs.push_back(std::move(frameMs));
                                      return rays;
                                  },
                                  [&, vi] { renderers[vi]->cache().clear(); }, [&, work] { context.progress.advance(work); }});
            }
            const std::vector<VariantTimes> movingTimes = runInterleaved(moving, 0, size.movingRounds);
            for (std::size_t k = 0; k < measuredIndex.size(); ++k) {
                VariantTimes perFrame = movingTimes[k];
                for (double& ms : perFrame.milliseconds) ms /= size.movingFrames;
                results[measuredIndex[k]].moving = perFrame;
            }
        }

        for (VariantResult& r : results) {
            if (!r.measured() || !results[0].measured()) continue;
            r.stillSpeedup = bootstrapSpeedup(results[0].still.milliseconds, r.still.milliseconds);
            if (!r.movingFrameMs.empty()) r.movingSpeedup = movingInterval(results[0], r);
        }

        // JSON row.
        nlohmann::json variantsJson = nlohmann::json::object();
        for (const VariantResult& r : results) {
            nlohmann::json v = {{"label", r.variant->label},
                                {"technique", techniqueName(r.variant->technique)},
                                {"documents_fps",
                                 finiteOrNull(spec_.documents.value(ts.label, r.variant->key).value_or(std::nan("")))}};
            if (r.variant->cdct)
                v["cdct"] = {{"step", r.variant->cdct->step},
                             {"epsilon", r.variant->cdct->epsilon},
                             {"max_depth", r.variant->cdct->maxDepth}};
            if (!r.measured()) {
                v["available"] = false;
                v["unavailable_reason"] = r.variant->unavailable;
            } else {
                v["available"] = true;
                v["still"] = toJson(r.still);
                v["still"]["speedup_vs_" + baseline.key] = toJson(r.stillSpeedup);
                v["still"]["cache_last_frame"] = lastFrameCacheJson(r.stillCache);
                if (!r.movingFrameMs.empty()) {
                    v["moving"] = toJson(r.moving);
                    v["moving"]["frame_ms_per_round"] = r.movingFrameMs;
                    v["moving"]["speedup_vs_" + baseline.key] = toJson(r.movingSpeedup);
                    v["moving"]["cache_last_frame"] = lastFrameCacheJson(r.movingLastCache);
                }
            }
            variantsJson[r.variant->key] = std::move(v);
        }
        rowsJson.push_back({{"scene", ts.scene},
                            {"label", ts.label},
                            {"still_timed_rounds", stillRun.rounds},
                            {"still_timed_seconds", stillRun.seconds},
                            {"still_stop_reason", toString(stillRun.reason)},
                            {"variants", variantsJson}});
        table.push_back(std::move(results));
    }

    // Markdown, plots, JSON.
    ExperimentOutput out;
    out.name = spec_.name;
    out.title = spec_.title;
    out.caveats = spec_.caveats;
    std::string md = spec_.description + "\n\n";
    md += "Size `" + toString(context.settings.size) + "`: " + std::to_string(size.width) + "x" +
          std::to_string(size.height) + ", " + std::to_string(size.cacheResolution) + "² cache faces, " +
          std::to_string(size.warmupFrames) + " warm-up + " + std::to_string(size.timedFrames) +
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
    for (std::size_t si = 0; si < stops.size(); ++si)
        md += (si ? "; " : "") + spec_.rowHeader + " = " + spec_.scenes[si].label + ": " +
              std::to_string(stops[si].rounds) + " (" + toString(stops[si].reason) + ", " +
              cellNumber(stops[si].seconds, 1) + " s)";
    md += ".\n\n";

    SvgPlot speedPlot;
    speedPlot.referenceY = 1.0;
    SvgPlot timePlot;
    timePlot.title = spec_.name + ": ms per frame, still camera, caches filled (median, min–max)";
    timePlot.yLabel = "ms per frame";
    for (std::size_t si = 0; si < table.size(); ++si) timePlot.categories.push_back(spec_.scenes[si].label);
    timePlot.xLabel = spec_.rowHeader;
    for (std::size_t vi = 0; vi < spec_.variants.size(); ++vi) {
        if (!spec_.variants[vi].unavailable.empty()) continue;
        PlotSeries series{spec_.variants[vi].label, {}};
        for (std::size_t si = 0; si < table.size(); ++si) {
            const SampleSummary s = summarize(table[si][vi].still.milliseconds);
            series.points.push_back({static_cast<double>(si), s.median, s.min, s.max});
        }
        timePlot.series.push_back(std::move(series));
    }

    if (spec_.rowsAreScenes) {
        const TimingVariant& compared = spec_.variants.at(1);
        const bool hasMoving = size.movingFrames > 0 && size.movingRounds > 0;
        std::vector<std::string> headers{
            spec_.rowHeader,       "documents: " + baseline.label + " fps", "documents: " + compared.label + " fps",
            "documents: speed-up", "raycache: " + baseline.label + " ms",   "raycache: " + compared.label + " ms",
            "raycache: speed-up"};
        if (hasMoving) {
            headers.push_back("moving camera: speed-up");
            headers.push_back(compared.label + " hit rate, last moving frame");
        }
        MarkdownTable t(headers);
        const std::string& source = spec_.documents.source;
        PlotSeries ours{"raycache, caches filled", {}}, oursMoving{"raycache, moving camera", {}},
            documents{"documents (" + source.substr(source.rfind(", ") + 2) + ")", {}};
        documents.dashed = true;
        for (std::size_t si = 0; si < table.size(); ++si) {
            const auto& r = table[si];
            const std::string& label = spec_.scenes[si].label;
            const double docBase = spec_.documents.value(label, baseline.key).value_or(std::nan(""));
            const double docComp = spec_.documents.value(label, compared.key).value_or(std::nan(""));
            const double docSpeed =
                spec_.documentsSpeedupColumn.empty()
                    ? docComp / docBase
                    : spec_.documents.value(label, spec_.documentsSpeedupColumn).value_or(std::nan(""));
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
        speedPlot.title = spec_.name + ": speed-up of " + compared.label + " over " + baseline.label +
                          " (whiskers: 95 % confidence interval)";
        speedPlot.xLabel = spec_.rowHeader;
        speedPlot.yLabel = "speed-up (×)";
        speedPlot.categories = timePlot.categories;
        speedPlot.series.push_back(std::move(ours));
        if (hasMoving) speedPlot.series.push_back(std::move(oursMoving));
        speedPlot.series.push_back(std::move(documents));
        if (!table.empty()) {
            const SpeedupInterval& first = table.front()[1].stillSpeedup;
            const SpeedupInterval& last = table.back()[1].stillSpeedup;
            std::string alike;
            for (std::size_t si = 0; si < table.size(); ++si)
                if (table[si][1].stillSpeedup.containsOne())
                    alike += (alike.empty() ? "" : ", ") + spec_.scenes[si].label;
            out.headlines.push_back(
                spec_.name + ": " + compared.label + " speed-up " + describeSpeedup(first) + " at " + spec_.rowHeader +
                " = " + spec_.scenes.front().label + " to " + describeSpeedup(last) + " at " + spec_.rowHeader + " = " +
                spec_.scenes[table.size() - 1].label + ", caches filled" +
                (alike.empty() ? "" : "; no measurable difference at " + spec_.rowHeader + " = " + alike) +
                "; documents " +
                cellNumber(spec_.documents.value(spec_.scenes.front().label, spec_.documentsSpeedupColumn)
                               .value_or(std::nan("")),
                           2) +
                "× to " +
                cellNumber(spec_.documents.value(spec_.scenes[table.size() - 1].label, spec_.documentsSpeedupColumn)
                               .value_or(std::nan("")),
                           2) +
                "×");
        }
    } else {
        std::vector<std::string> headers{"variant"};
        for (std::size_t si = 0; si < table.size(); ++si) {
            const std::string& label = spec_.scenes[si].label;
            headers.push_back(label + ": documents fps");
            headers.push_back(label + ": documents × " + baseline.label);
            headers.push_back(label + ": raycache ms");
            headers.push_back(label + ": raycache × " + baseline.label);
            headers.push_back(label + ": hit rate");
        }
        MarkdownTable t(headers);
        speedPlot.title = spec_.name + ": frame rate relative to " + baseline.label +
                          " (higher is faster; whiskers: 95 % confidence interval)";
        speedPlot.yLabel = "× " + baseline.label + " frame rate";
        speedPlot.bars = true;
        speedPlot.height = 480;
        for (const TimingVariant& v : spec_.variants) speedPlot.categories.push_back(v.label);
        std::vector<PlotSeries> oursSeries(table.size()), docsSeries(table.size());
        for (std::size_t si = 0; si < table.size(); ++si) {
            oursSeries[si].name = spec_.scenes[si].label + ", raycache";
            docsSeries[si].name = spec_.scenes[si].label + ", documents";
            docsSeries[si].dashed = true;
        }
        for (std::size_t vi = 0; vi < spec_.variants.size(); ++vi) {
            const TimingVariant& v = spec_.variants[vi];
            std::vector<std::string> row{v.label};
            for (std::size_t si = 0; si < table.size(); ++si) {
                const std::string& label = spec_.scenes[si].label;
                const double docFps = spec_.documents.value(label, v.key).value_or(std::nan(""));
                const double docBase = spec_.documents.value(label, baseline.key).value_or(std::nan(""));
                row.push_back(cellNumber(docFps, 1));
                row.push_back(std::isfinite(docFps / docBase) ? cellNumber(docFps / docBase, 2) + "×" : "–");
                docsSeries[si].points.push_back({static_cast<double>(vi), docFps / docBase});
                if (!table[si][vi].measured()) {
                    row.push_back("not available in this build");
                    row.push_back("–");
                    row.push_back("–");
                    oursSeries[si].points.push_back({static_cast<double>(vi), std::nan("")});
                    continue;
                }
                const SampleSummary s = summarize(table[si][vi].still.milliseconds);
                const SpeedupInterval& rel = table[si][vi].stillSpeedup;
                row.push_back(cellRange(s, 1));
                row.push_back(vi == 0 ? "1.00×" : speedupCell(rel));
                row.push_back(table[si][vi].stillCache ? cellNumber(hitPercent(table[si][vi].stillCache), 1) + "%"
                                                       : "–");
                oursSeries[si].points.push_back(intervalPoint(static_cast<double>(vi), rel));
                if (vi > 0)
                    out.headlines.push_back(
                        spec_.name + " " + spec_.scenes[si].label + ": " + v.label + " vs " + baseline.label + ": " +
                        describeSpeedup(rel) + ", documents " +
                        (std::isfinite(docFps / docBase) ? cellNumber(docFps / docBase, 2) + "×" : "–") +
                        ", cache hit rate " + cellNumber(hitPercent(table[si][vi].stillCache), 1) + "%");
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
    for (const TimingVariant& v : spec_.variants)
        if (!v.unavailable.empty()) out.caveats.push_back(v.label + ": " + v.unavailable);
    const CpuSample cpuAfter = currentCpuSample();
    const LoadAverage loadAfter = currentLoadAverage();
    const double othersShare = othersCpuShare(cpuBefore, cpuAfter);
    md += "Other processes used " + formatOthersShare(othersShare) +
          " of the machine's CPU time while this table ran. " +
          "Load average (1, 5, 15 min): " + loadBefore.toString() + " before, " + loadAfter.toString() +
          " after (it includes the bench's own earlier work).\n\n";
    if (const std::string busy = busyMachineWarning(othersShare, loadBefore, loadAfter, cpuAfter.cpus); !busy.empty())
        out.caveats.push_back(busy);

    writeSvgPlot(speedPlot, (context.dir / "speedup.svg").string());
    writeSvgPlot(timePlot, (context.dir / "frame-times.svg").string());
    out.plots = {"speedup.svg", "frame-times.svg"};
    out.markdown = md;

    nlohmann::json variantsSpec = nlohmann::json::array();
    for (const TimingVariant& v : spec_.variants)
        variantsSpec.push_back({{"key", v.key},
                                {"label", v.label},
                                {"technique", techniqueName(v.technique)},
                                {"available", v.unavailable.empty()}});
    // null where /proc/stat could not be read
    const nlohmann::json othersJson = othersShare >= 0.0 ? nlohmann::json(othersShare) : nlohmann::json();
    const nlohmann::json root = {{"experiment", spec_.name},
                                 {"title", spec_.title},
                                 {"size", toString(context.settings.size)},
                                 {"settings",
                                  {{"width", size.width},
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
                                   {"pipeline", spec_.pipeline},
                                   {"variants", variantsSpec}}},
                                 {"environment", toJson(context.environment)},
                                 {"documents", toJson(spec_.documents)},
                                 {"load_average", {{"before", loadBefore.toString()}, {"after", loadAfter.toString()}}},
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
