#include "bench/DynamicExperiment.h"

#include <array>
#include <chrono>
#include <cmath>
#include <functional>

#include "bench/MarkdownTable.h"
#include "bench/ResultsJson.h"
#include "bench/SvgPlot.h"
#include "core/AtomicFile.h"
#include "core/Elapsed.h"
#include "core/Errors.h"
#include "core/SampleSummary.h"
#include "metrics/ImageMetrics.h"
#include "scene/BuiltinScenes.h"
#include "session/InvalidationOracle.h"
#include "session/RenderSession.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kDynamicScenes[] = {"room-moving", "orbit", "cloth", "light-sweep"};

int dynamicImageSide(BenchSize size) { return size == BenchSize::Tiny ? 48 : size == BenchSize::Quick ? 512 : 1024; }
int dynamicFrameCount(BenchSize size) { return size == BenchSize::Tiny ? 3 : size == BenchSize::Quick ? 24 : 60; }
// The oracle traces every valid texel again after each change. It runs
// twice: as the frames are timed (their image size, the scenes' own cubes:
// what the goal counts), and coarse (a 256² image, 64² faces), where
// a block of 8x8 texels spans 8 times the angle of a 512² face's, so its
// union of trees is wider and more of its drops are needless: the harder test.
struct OracleProtocol {
    const char* name;
    int side;
    int resolution;  // 0: the scenes' own
};
std::array<OracleProtocol, 2> oracleProtocols(BenchSize size) {
    return {OracleProtocol{"as timed", dynamicImageSide(size), 0},
            OracleProtocol{"coarse", size == BenchSize::Tiny ? 32 : 256, 64}};
}
int oracleChanges(BenchSize size) { return size == BenchSize::Tiny ? 1 : 5; }
float oracleStart(const Scene& scene) { return scene.animation.duration() / 3.0f; }

nlohmann::json oracleJson(const InvalidationCounts& o) {
    return {{"checked", o.checked},
            {"kept", o.kept},
            {"stale", o.stale},
            {"dropped", o.dropped},
            {"needless", o.needless},
            {"changed", o.changed()},
            {"moved_cube", o.movedCube},
            {"moved_cube_within_tolerance", o.movedCubeWithinTolerance},
            {"moved_cube_kept", o.movedCubeKept}};
}

struct DynamicSceneRun {
    std::string scene;
    std::vector<double> uncachedMs, cctMs, updateMs, psnrDb, hitPercent;
    // CCT with every store made (RayCacheSettings::skipStoresReachingChanges off).
    std::vector<double> everyStoreMs, everyStoreUpdateMs;
    std::vector<std::int64_t> texelsDropped;
    std::array<InvalidationCounts, 2> oracle;  // per oracleProtocols()
};

class DynamicExperiment : public Experiment {
public:
    std::string name() const override { return "dynamic"; }
    std::string title() const override {
        return "Dynamic scenes: CCT with per-block invalidation against uncached, along the built-in animations";
    }
    double estimatedWork(const BenchSettings& settings) const override {
        const double mp = std::pow(dynamicImageSide(settings.size), 2) / 1e6;
        return std::size(kDynamicScenes) * dynamicFrameCount(settings.size) * 3.0 * mp;
    }

    ExperimentOutput run(ExperimentContext& context) const override {
        const BenchSize size = context.settings.size;
        const int side = dynamicImageSide(size), frames = dynamicFrameCount(size);
        std::vector<DynamicSceneRun> runs;
        for (const char* name : kDynamicScenes) {
            context.progress.step("dynamic: " + std::string(name));
            runs.push_back(runScene(name, side, frames, context));
        }
        return report(runs, side, frames, context);
    }

    bool honoursCachePolicy() const override { return true; }

private:
    static RenderSettings settingsFor(int side, const BenchSettings& bench, CacheTechnique technique) {
        RenderSettings s;
        s.width = s.height = side;
        s.threads = bench.threads;
        s.cache.techniqueOverride = technique;
        s.cache.policy = bench.cachePolicy;  // the oracle's cubes always cache (RayCache)
        return s;
    }

    static DynamicSceneRun runScene(const std::string& name, int side, int frames, ExperimentContext& context) {
        const std::optional<Scene> scene = makeBuiltinScene(name);
        if (!scene) throw RuntimeError("built-in scene " + name + " is missing");
        DynamicSceneRun run{name, {}, {}, {}, {}, {}, {}, {}, {}, {}};
        const BenchSettings& bench = context.settings;
        RenderSession uncached(*scene, settingsFor(side, bench, CacheTechnique::None));
        RenderSession cct(*scene, settingsFor(side, bench, CacheTechnique::Cct));
        RenderSettings everyStoreSettings = settingsFor(side, bench, CacheTechnique::Cct);
        everyStoreSettings.cache.skipStoresReachingChanges = false;
        RenderSession everyStore(*scene, everyStoreSettings);
        Image truth, film, everyStoreFilm;
        const double frameWork = static_cast<double>(side) * side / 1e6;
        for (int f = 0; f < frames; ++f) {
            const float time = static_cast<float>(f) / scene->fps;
            // Alternate which goes first, so drifts of the machine hit both alike.
            const auto timeUncached = [&] {
                const auto start = Clock::now();
                uncached.setTime(time);
                uncached.render(scene->camera, truth);
                run.uncachedMs.push_back(millisecondsSince(start));
            };
            FrameStats stats;
            const auto timeCct = [&] {
                const auto start = Clock::now();
                cct.setTime(time);
                stats = cct.render(scene->camera, film);
                run.cctMs.push_back(millisecondsSince(start));
            };
            const auto timeEveryStore = [&] {
                const auto start = Clock::now();
                everyStore.setTime(time);
                const FrameStats everyStats = everyStore.render(scene->camera, everyStoreFilm);
                run.everyStoreMs.push_back(millisecondsSince(start));
                run.everyStoreUpdateMs.push_back(everyStats.sceneUpdate ? everyStats.sceneUpdate->milliseconds : 0.0);
            };
            // Rotate the order, so drifts of the machine hit all three alike.
            const std::function<void()> order[] = {timeUncached, timeCct, timeEveryStore};
            for (int k = 0; k < 3; ++k) order[(f + k) % 3]();
            run.updateMs.push_back(stats.sceneUpdate ? stats.sceneUpdate->milliseconds : 0.0);
            run.texelsDropped.push_back(stats.sceneUpdate ? stats.sceneUpdate->texelsInvalidated : 0);
            const FrameCacheStats& c = *stats.cache;
            run.hitPercent.push_back(c.lookups() ? 100.0 * static_cast<double>(c.hits()) / static_cast<double>(c.lookups())
                                                 : 0.0);
            run.psnrDb.push_back(psnr(film, truth));
            context.progress.advance(3.0 * frameWork);
        }
        // The oracle, in sessions of its own (every lookup misses there).
        const std::array<OracleProtocol, 2> protocols = oracleProtocols(context.settings.size);
        for (std::size_t p = 0; p < protocols.size(); ++p) {
            RenderSettings oracleSettings = settingsFor(protocols[p].side, bench, CacheTechnique::Cct);
            if (protocols[p].resolution > 0) oracleSettings.cache.resolutionOverride = protocols[p].resolution;
            oracleSettings.cache.invalidationOracle = true;
            // From a third into the animation: eased keys start at rest, where
            // frames barely differ.
            RenderSession checked(*scene, oracleSettings);
            const float start = oracleStart(*scene);
            for (int f = 0; f < oracleChanges(context.settings.size); ++f) {
                checked.setTime(start + static_cast<float>(f) / scene->fps);
                checked.render(scene->camera, film);
                InvalidationOracle oracle;
                oracle.take(checked);
                checked.setTime(start + static_cast<float>(f + 1) / scene->fps);
                run.oracle[p] += oracle.check(checked);
            }
        }
        return run;
    }

    ExperimentOutput report(const std::vector<DynamicSceneRun>& runs, int side, int frames, ExperimentContext& context) const {
        ExperimentOutput out;
        out.name = name();
        out.title = title();
        std::string md = "Each built-in animated scene at " + std::to_string(side) + "x" + std::to_string(side) +
                         ", " + std::to_string(frames) +
                         " frames from t = 0 at the scene's fps, the camera still. Uncached, CCT and CCT making "
                         "every store (without skipping those that reached what the last change moved) render "
                         "each frame in turn (the order rotating), each timed from its scene update to its "
                         "finished image. Medians with min–max over frames 1 to " +
                         std::to_string(frames - 1) + " (frame 0 fills the caches). PSNR: the CCT frame against "
                         "the uncached frame of the same pose.\n\n";
        MarkdownTable speed({"scene", "uncached ms", "CCT ms", "CCT speed-up (ratio of medians)", "per-frame ratio",
                             "update share of the CCT frame", "CCT hits", "texels dropped per frame", "PSNR min / median",
                             "CCT, every store: ms", "its speed-up", "its update share"});
        nlohmann::json series = nlohmann::json::array();
        SvgPlot plot;
        plot.title = "dynamic: uncached / CCT frame time, per frame";
        plot.xLabel = "frame";
        plot.yLabel = "speed-up of CCT";
        plot.referenceY = 1.0;
        for (const DynamicSceneRun& r : runs) {
            const auto tail = [](const std::vector<double>& v) {
                return v.size() > 1 ? std::vector<double>(v.begin() + 1, v.end()) : v;
            };
            const SampleSummary u = summarize(tail(r.uncachedMs)), c = summarize(tail(r.cctMs));
            const SampleSummary every = summarize(tail(r.everyStoreMs));
            std::vector<double> ratio, share, dropped, everyShare;
            for (std::size_t f = 0; f < r.everyStoreMs.size(); ++f)
                everyShare.push_back(100.0 * r.everyStoreUpdateMs[f] / r.everyStoreMs[f]);
            PlotSeries s{r.scene, {}};
            for (std::size_t f = 0; f < r.cctMs.size(); ++f) {
                ratio.push_back(r.uncachedMs[f] / r.cctMs[f]);
                share.push_back(100.0 * r.updateMs[f] / r.cctMs[f]);
                dropped.push_back(static_cast<double>(r.texelsDropped[f]));
                s.points.push_back({static_cast<double>(f), ratio.back()});
            }
            plot.series.push_back(std::move(s));
            const SampleSummary ratioSummary = summarize(tail(ratio)), shareSummary = summarize(tail(share));
            const SampleSummary hits = summarize(tail(r.hitPercent)), drops = summarize(tail(dropped));
            std::vector<double> finitePsnr;
            for (double p : r.psnrDb) finitePsnr.push_back(std::isfinite(p) ? p : 99.0);
            const SampleSummary quality = summarize(tail(finitePsnr));
            speed.addRow({r.scene, cellRange(u, 1), cellRange(c, 1), cellNumber(u.median / c.median, 2) + "×",
                          cellRange(ratioSummary, 2) + "×", cellRange(shareSummary, 1) + " %",
                          cellRange(hits, 1) + " %", cellRange(drops, 0),
                          cellNumber(quality.min, 1) + " / " + cellNumber(quality.median, 1) + " dB",
                          cellRange(every, 1), cellNumber(u.median / every.median, 2) + "×",
                          cellRange(summarize(tail(everyShare)), 1) + " %"});
            out.headlines.push_back("dynamic " + r.scene + ": CCT " + cellNumber(u.median / c.median, 2) +
                                    "× uncached, PSNR ≥ " + cellNumber(quality.min, 1) + " dB, " +
                                    std::to_string(r.oracle[0].stale + r.oracle[1].stale) + " stale texels");
            series.push_back({{"scene", r.scene},
                              {"uncached_ms", r.uncachedMs},
                              {"cct_ms", r.cctMs},
                              {"cct_every_store_ms", r.everyStoreMs},
                              {"cct_every_store_update_ms", r.everyStoreUpdateMs},
                              {"update_ms", r.updateMs},
                              {"hit_percent", r.hitPercent},
                              {"texels_dropped", r.texelsDropped},
                              {"psnr_db", finitePsnr},
                              {"oracle", {{"as_timed", oracleJson(r.oracle[0])}, {"coarse", oracleJson(r.oracle[1])}}}});
        }
        md += speed.toMarkdown();
        md += "\nPSNR 99 stands for identical images.\n\n";
        const std::array<OracleProtocol, 2> protocols = oracleProtocols(context.settings.size);
        md += "**Invalidation oracle**, " + std::to_string(oracleChanges(context.settings.size)) +
              " changes from a third into the animation; every lookup misses so each texel holds its ray's uncached "
              "colour; after each change every texel valid before it is traced again in the new pose: stale = kept but "
              "now different; needless = dropped but unchanged; changed = texels whose colour the change altered. A "
              "caching object that moves takes its cube along; its texels' rays started where it was, so it drops "
              "them, except (a sphere that only moved) those whose rays escaped to the environment and, moved along, "
              "still do. The last three columns: those texels, how many the cache kept, and how many would have "
              "stayed within 1/255 of the truth, re-traced from the moved origin, had all been kept. Two protocols: "
              "*as timed* (" + std::to_string(protocols[0].side) + "² image, the scenes' own cubes) and *coarse* (" +
              std::to_string(protocols[1].side) + "² image, " + std::to_string(protocols[1].resolution) +
              "² faces: each 8x8 block spans a wider angle, so its union of trees is looser).\n\n";
        MarkdownTable oracle({"scene", "protocol", "texels checked", "kept", "stale", "dropped", "needless", "changed",
                              "needless / changed", "texels of moving caching objects", "of them kept",
                              "of them within 1/255 if all kept"});
        for (std::size_t p = 0; p < protocols.size(); ++p)
            for (const DynamicSceneRun& r : runs) {
                const InvalidationCounts& o = r.oracle[p];
                const std::int64_t changed = o.changed();
                oracle.addRow({r.scene, protocols[p].name, std::to_string(o.checked), std::to_string(o.kept),
                               std::to_string(o.stale), std::to_string(o.dropped), std::to_string(o.needless),
                               std::to_string(changed),
                               changed > 0 ? cellNumber(static_cast<double>(o.needless) / static_cast<double>(changed), 1)
                                           : std::string("–"),
                               std::to_string(o.movedCube), std::to_string(o.movedCubeKept),
                               o.movedCube > 0 ? cellNumber(100.0 * static_cast<double>(o.movedCubeWithinTolerance) /
                                                                static_cast<double>(o.movedCube),
                                                            1) + " %"
                                               : std::string("–")});
            }
        md += oracle.toMarkdown();
        out.markdown = md;
        writeSvgPlot(plot, (context.dir / "speedup-per-frame.svg").string());
        out.plots = {"speedup-per-frame.svg"};
        writeJsonFile(context.dir / "results.json",
                      {{"experiment", name()},
                       {"title", title()},
                       {"size", toString(context.settings.size)},
                       {"settings",
                        {{"width", side},
                         {"height", side},
                         {"frames", frames},
                         {"oracle_as_timed_side", protocols[0].side},
                         {"oracle_coarse_side", protocols[1].side},
                         {"oracle_coarse_resolution", protocols[1].resolution},
                         {"oracle_changes", oracleChanges(context.settings.size)},
                         {"cache_policy", cachePolicyModeName(context.settings.cachePolicy)}}},
                       {"environment", toJson(context.environment)},
                       {"series", series}});
        writeTextFileAtomically(context.dir / "results.md", experimentMarkdown(out));
        return out;
    }
};

}  // namespace

std::unique_ptr<Experiment> makeDynamicExperiment() { return std::make_unique<DynamicExperiment>(); }

}  // namespace raycache
