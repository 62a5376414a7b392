#include "bench/TimingTableExperiment.h"

#include <chrono>
#include <cmath>

#include "bench/InterleavedRuns.h"
#include "bench/MarkdownTable.h"
#include "bench/ResultsJson.h"
#include "bench/SampleSummary.h"
#include "bench/SvgPlot.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "render/FramePipeline.h"
#include "scene/BuiltinScenes.h"
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
    bool measured() const { return variant->unavailable.empty(); }
};

nlohmann::json cacheJson(const std::optional<FrameCacheStats>& c) {
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

double ratio(double baselineMs, double ms) {
    return ms > 0.0 && baselineMs > 0.0 ? baselineMs / ms : std::nan("");
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
        std::vector<std::unique_ptr<RayCache>> caches(spec_.variants.size());
        std::vector<std::unique_ptr<FramePipeline>> renderers(spec_.variants.size());
        for (std::size_t vi = 0; vi < spec_.variants.size(); ++vi) {
            const TimingVariant& v = spec_.variants[vi];
            results[vi].variant = &v;
            if (!v.unavailable.empty()) continue;
            RenderSettings& s = settings[vi];
            s.width = size.width;
            s.height = size.height;
            s.threads = context.settings.threads;
            s.cache.techniqueOverride = v.technique;
            s.cache.resolutionOverride = size.cacheResolution;
            if (v.cdct) {
                s.cache.cdctStepOverride = v.cdct->step;
                s.cache.cdctEpsilonOverride = v.cdct->epsilon;
                s.cache.cdctMaxDepthOverride = v.cdct->maxDepth;
            }
            if (spec_.configure) spec_.configure(s);
            caches[vi] = std::make_unique<RayCache>(scene, s.cache);
            renderers[vi] = makeFramePipeline(scene, tracer, s, context.parallel, caches[vi].get());
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
        const std::vector<VariantTimes> stillTimes = runInterleaved(still, size.warmupFrames, size.timedFrames);
        for (std::size_t k = 0; k < measuredIndex.size(); ++k) results[measuredIndex[k]].still = stillTimes[k];

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
                                  [&, vi] { caches[vi]->clear(); }, [&, work] { context.progress.advance(work); }});
            }
            const std::vector<VariantTimes> movingTimes = runInterleaved(moving, 0, size.movingRounds);
            for (std::size_t k = 0; k < measuredIndex.size(); ++k) {
                VariantTimes perFrame = movingTimes[k];
                for (double& ms : perFrame.milliseconds) ms /= size.movingFrames;
                results[measuredIndex[k]].moving = perFrame;
            }
        }

        // JSON row.
        const double baseStill = summarize(results[0].still.milliseconds).median;
        const double baseMoving = summarize(results[0].moving.milliseconds).median;
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
                v["still"]["speedup_vs_" + baseline.key] =
                    finiteOrNull(ratio(baseStill, summarize(r.still.milliseconds).median));
                v["still"]["cache_last_frame"] = cacheJson(r.stillCache);
                if (!r.movingFrameMs.empty()) {
                    v["moving"] = toJson(r.moving);
                    v["moving"]["frame_ms_per_round"] = r.movingFrameMs;
                    v["moving"]["speedup_vs_" + baseline.key] =
                        finiteOrNull(ratio(baseMoving, summarize(r.moving.milliseconds).median));
                    v["moving"]["cache_last_frame"] = cacheJson(r.movingLastCache);
                }
            }
            variantsJson[r.variant->key] = std::move(v);
        }
        rowsJson.push_back({{"scene", ts.scene}, {"label", ts.label}, {"variants", variantsJson}});
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
          " timed frames per variant (still camera, variants interleaved)";
    if (size.movingFrames > 0)
        md += "; moving camera: the scene's path, " + std::to_string(size.movingFrames) +
              " frames from empty caches, " + std::to_string(size.movingRounds) + " run(s) per variant";
    md +=
        ". Times are ms per frame, median (min–max); speed-up = uncached median / variant median. "
        "The documents' figures are GPU frame rates: compare speed-ups, not frame rates.\n\n";

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
            const double speed = ratio(b.median, c.median);
            std::vector<std::string> row{label,
                                         cellNumber(docBase, 1),
                                         cellNumber(docComp, 1),
                                         cellNumber(docSpeed, 2) + (std::isfinite(docSpeed) ? "×" : ""),
                                         cellRange(b, 1),
                                         cellRange(c, 1),
                                         cellNumber(speed, 2) + "×"};
            double movingSpeed = std::nan("");
            if (hasMoving) {
                movingSpeed =
                    ratio(summarize(r[0].moving.milliseconds).median, summarize(r[1].moving.milliseconds).median);
                row.push_back(cellNumber(movingSpeed, 2) + "×");
                row.push_back(cellNumber(hitPercent(r[1].movingLastCache), 1) + "%");
            }
            t.addRow(row);
            ours.points.push_back({static_cast<double>(si), speed});
            oursMoving.points.push_back({static_cast<double>(si), movingSpeed});
            documents.points.push_back({static_cast<double>(si), docSpeed});
        }
        md += t.toMarkdown();
        speedPlot.title = spec_.name + ": speed-up of " + compared.label + " over " + baseline.label;
        speedPlot.xLabel = spec_.rowHeader;
        speedPlot.yLabel = "speed-up (×)";
        speedPlot.categories = timePlot.categories;
        speedPlot.series.push_back(std::move(ours));
        if (hasMoving) speedPlot.series.push_back(std::move(oursMoving));
        speedPlot.series.push_back(std::move(documents));
        if (!table.empty()) {
            const double first = ratio(summarize(table.front()[0].still.milliseconds).median,
                                       summarize(table.front()[1].still.milliseconds).median);
            const double last = ratio(summarize(table.back()[0].still.milliseconds).median,
                                      summarize(table.back()[1].still.milliseconds).median);
            out.headlines.push_back(
                spec_.name + ": " + compared.label + " speed-up " + cellNumber(first, 2) + "× (" + spec_.rowHeader +
                " = " + spec_.scenes.front().label + ") to " + cellNumber(last, 2) + "× (" + spec_.rowHeader + " = " +
                spec_.scenes[table.size() - 1].label + "), caches filled; documents " +
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
        speedPlot.title = spec_.name + ": frame rate relative to " + baseline.label + " (higher is faster)";
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
                const double rel = ratio(summarize(table[si][0].still.milliseconds).median, s.median);
                row.push_back(cellRange(s, 1));
                row.push_back(cellNumber(rel, 2) + "×");
                row.push_back(table[si][vi].stillCache ? cellNumber(hitPercent(table[si][vi].stillCache), 1) + "%"
                                                       : "–");
                oursSeries[si].points.push_back({static_cast<double>(vi), rel});
                if (vi > 0)
                    out.headlines.push_back(
                        spec_.name + " " + spec_.scenes[si].label + ": " + v.label + " " + cellNumber(rel, 2) + "× " +
                        baseline.label + " (documents " +
                        (std::isfinite(docFps / docBase) ? cellNumber(docFps / docBase, 2) + "×" : "–") +
                        "), cache hit rate " + cellNumber(hitPercent(table[si][vi].stillCache), 1) + "%");
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
    const nlohmann::json root = {{"experiment", spec_.name},
                                 {"title", spec_.title},
                                 {"size", toString(context.settings.size)},
                                 {"settings",
                                  {{"width", size.width},
                                   {"height", size.height},
                                   {"cache_resolution", size.cacheResolution},
                                   {"warmup_frames", size.warmupFrames},
                                   {"timed_frames", size.timedFrames},
                                   {"moving_frames", size.movingFrames},
                                   {"moving_rounds", size.movingRounds},
                                   {"max_depth", RenderSettings{}.maxDepth},
                                   {"pipeline", spec_.pipeline},
                                   {"variants", variantsSpec}}},
                                 {"environment", toJson(context.environment)},
                                 {"documents", toJson(spec_.documents)},
                                 {"caveats", out.caveats},
                                 {"rows", rowsJson}};
    writeJsonFile(context.dir / "results.json", root);
    writeTextFileAtomically(context.dir / "results.md", experimentMarkdown(out));
    return out;
}

}  // namespace raycache
