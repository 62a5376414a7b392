#include "bench/RenderCacheExperiment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>

#include "bench/AsyncDisplayMeasurement.h"
#include "bench/ImageComparison.h"
#include "bench/MachineLoad.h"
#include "bench/MarkdownTable.h"
#include "bench/PaperFigures.h"
#include "bench/ResultsJson.h"
#include "bench/SpeedupInterval.h"
#include "bench/SvgPlot.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/SampleSummary.h"
#include "core/TextFormat.h"
#include "metrics/Heatmap.h"
#include "metrics/ImageMetrics.h"
#include "render/CameraRays.h"
#include "render/ImageWriter.h"
#include "rendercache/ReshadeBudget.h"
#include "scene/BuiltinScenes.h"
#include "scene/MeshSearchPath.h"
#include "scene/RealMeshScenes.h"
#include "session/RenderSession.h"
#include "trace/TraceScene.h"

namespace raycache {

namespace {

// Each scene's own camera path. dragon-hall (0.87 M triangles behind its
// mirrors: the expensive scene, where the Render Cache should pay most) is
// left out of the tiny runs the tests make.
std::vector<std::string> benchScenes(BenchSize size) {
    std::vector<std::string> scenes = {"room", "behind-32", "glass"};
    if (size != BenchSize::Tiny) scenes.push_back("dragon-hall");
    return scenes;
}

// A built-in scene, or one made of real meshes found on the search path;
// empty, with a caveat saying why, when its mesh is not there.
std::optional<Scene> benchScene(const std::string& name, std::vector<std::string>& caveats) {
    if (std::optional<Scene> scene = makeBuiltinScene(name)) return scene;
    const MeshSearchPath meshes = meshSearchPathFromEnvironment();
    const auto real = realMeshScenes();
    const auto info =
        std::find_if(real.begin(), real.end(), [&](const RealMeshSceneInfo& r) { return r.name == name; });
    if (info == real.end()) throw RuntimeError("built-in scene " + name + " is missing");
    if (const std::string missing = missingMeshFiles(*info, meshes); !missing.empty()) {
        const std::string caveat =
            name + " left out: its mesh is not on the search path (" + missing + "; scripts/install-deps.sh fetches it)";
        if (std::find(caveats.begin(), caveats.end(), caveat) == caveats.end()) caveats.push_back(caveat);
        return std::nullopt;
    }
    return makeRealMeshScene(name, meshes);
}

std::string sceneNamesListed(const std::vector<std::string>& names, const char* quote) {
    std::string text;
    for (std::size_t i = 0; i < names.size(); ++i) text += (i ? ", " : "") + (quote + names[i] + quote);
    return text;
}

struct RcVariant {
    std::string key;
    std::string label;
    ReprojectedReflections reflections;
};

std::vector<RcVariant> rcVariants() {
    return {{"reproject", "Render Cache", ReprojectedReflections::Reproject},
            {"reshade", "Render Cache + re-evaluated reflections", ReprojectedReflections::Reshade}};
}

// Our goals (not the documents'): targets the measured numbers are checked against.
constexpr double kGoalReconstructionMs512 = 2.0;
constexpr double kGoalReconstructionMs1024 = 8.0;
constexpr double kGoalFps = 60.0;
constexpr int kGoalFpsSide = 1024;
constexpr double kGoalMeanPsnr = 30.0;
constexpr double kGoalMirrorGainDb = 3.0;
const std::vector<std::string> kEndToEndGoalScenes = {"room", "behind-32"};

// Frame 1 traces every pixel (there are no samples yet): left out of every summary.
constexpr std::size_t kSkippedFrames = 1;

std::vector<int> imageSides(BenchSize size) {
    switch (size) {
        case BenchSize::Full:
            return {512, 1024};
        case BenchSize::Quick:
            return {512};
        case BenchSize::Tiny:
            return {48};
    }
    return {};
}

int renderCacheFrameCount(BenchSize size) {
    return size == BenchSize::Full ? 60 : size == BenchSize::Quick ? 30 : 4;
}

std::string sideText(int side) {
    return std::to_string(side) + "²";
}

struct FrameRecord {
    double ms = 0.0;
    RenderCacheStats rc;
    ImageComparison metrics;
    double mirrorPsnr = 0.0;  // NaN without mirror pixels, +infinity when they are identical
};

struct VariantRun {
    std::vector<FrameRecord> frames;
    SpeedupInterval speedup;  // end to end over the full render, frames after the first
};

// The asynchronous display's two reshading budgets: every sample every
// frame, and the viewer's default.
struct AsyncBudget {
    std::string key;
    std::string label;
    double reshadeMs;
};

std::vector<AsyncBudget> asyncBudgets() {
    return {{"async_every_frame", "async display, every sample reshaded every frame", 0.0},
            {"async_budget", "async display, reshading within " + formatShortestFloat(static_cast<float>(kDefaultReshadeBudgetMs)) + " ms",
             kDefaultReshadeBudgetMs}};
}

struct SceneRun {
    std::string scene;
    int side = 0;
    std::vector<double> fullMs;
    std::vector<std::int64_t> mirrorPixels;  // per frame
    std::vector<VariantRun> variants;        // as rcVariants()
    std::vector<AsyncDisplayResult> async;   // as asyncBudgets()
};

// The values of frames after the skipped ones.
template <typename Get>
std::vector<double> series(const std::vector<FrameRecord>& frames, Get get) {
    std::vector<double> out;
    for (std::size_t f = frames.size() > kSkippedFrames ? kSkippedFrames : 0; f < frames.size(); ++f)
        out.push_back(get(frames[f]));
    return out;
}

std::vector<double> afterSkipped(const std::vector<double>& values) {
    if (values.size() <= kSkippedFrames) return values;
    return {values.begin() + static_cast<std::ptrdiff_t>(kSkippedFrames), values.end()};
}

std::vector<double> finiteOnly(const std::vector<double>& values) {
    std::vector<double> out;
    std::copy_if(values.begin(), values.end(), std::back_inserter(out), [](double v) { return std::isfinite(v); });
    return out;
}

double mean(const std::vector<double>& values) {
    if (values.empty()) return std::nan("");
    return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

// Median, range and mean of the finite values; nulls when there are none.
nlohmann::json summaryJson(const std::vector<double>& values) {
    const std::vector<double> finite = finiteOnly(values);
    if (finite.empty())
        return {{"median", nullptr}, {"min", nullptr}, {"max", nullptr}, {"mean", nullptr}, {"count", 0}};
    const SampleSummary s = summarize(finite);
    return {{"median", s.median}, {"min", s.min}, {"max", s.max}, {"mean", mean(finite)}, {"count", finite.size()}};
}

// "median (min–max)" of the finite values, "–" without any.
std::string rangeCell(const std::vector<double>& values, int decimals) {
    const std::vector<double> finite = finiteOnly(values);
    return finite.empty() ? "–" : cellRange(summarize(finite), decimals);
}

// PSNR cells: identical frames are infinite and counted apart.
std::string psnrCell(const std::vector<double>& values) {
    const std::vector<double> finite = finiteOnly(values);
    const auto identical = std::count_if(values.begin(), values.end(), [](double v) { return std::isinf(v); });
    std::string cell = finite.empty() ? (identical > 0 ? "∞" : "–") : cellRange(summarize(finite), 2);
    if (identical > 0 && !finite.empty()) cell += ", " + std::to_string(identical) + " identical";
    return cell;
}

double medianOf(const std::vector<double>& values) {
    const std::vector<double> finite = finiteOnly(values);
    return finite.empty() ? std::nan("") : summarize(finite).median;
}

// Pixels whose first hit is an object that reflects (mirrors, and glass,
// which reflects part of its light): the first hits of the full render, found
// by tracing its primary rays.
std::vector<unsigned char> mirrorMask(const Scene& scene, const TraceScene& tracer, const Camera& camera, int side,
                                      const Parallel& parallel) {
    std::vector<unsigned char> mask(static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0);
    const CameraRays rays(camera, side, side);
    parallel.forEachIndex(side, [&](int y, int) {
        for (int x = 0; x < side; ++x) {
            const TraceHit hit = tracer.intersect(rays.ray(x, y));
            mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(side) + static_cast<std::size_t>(x)] =
                hit.hit() && scene.objects[static_cast<std::size_t>(hit.objectId)].material.reflects() ? 1 : 0;
        }
    });
    return mask;
}

nlohmann::json frameJson(int frame, const FrameRecord& r, std::int64_t mirrorPixels) {
    const RenderCacheStats& s = r.rc;
    nlohmann::json j = toJson(r.metrics);
    j.update(renderCacheStatsJson(s));  // as `raycache render --stats` writes them
    j["frame"] = frame;
    j["ms"] = r.ms;
    j["fresh_share"] = s.freshShare();
    j["mirror_pixels"] = mirrorPixels;
    j["mirror_psnr_db"] = finiteOrNull(r.mirrorPsnr);
    return j;
}

// One goal checked in one place: met, not met, or not measured.
struct GoalCheck {
    std::string goal;
    std::string where;
    std::string measured;
    std::optional<bool> met;  // nullopt: not measured in this run
};

std::string metText(const std::optional<bool>& met) {
    return !met ? "not measured" : *met ? "met" : "not met";
}

class RenderCacheExperiment : public Experiment {
public:
    std::string name() const override { return "render-cache"; }
    std::string title() const override {
        return "Render Cache: frame time split and quality along camera paths (" +
               sceneNamesListed(benchScenes(BenchSize::Full), "") + ")";
    }
    double estimatedWork(const BenchSettings& settings) const override {
        double work = 0.0;
        for (int side : imageSides(settings.size))
            work += renderCacheFrameCount(settings.size) * static_cast<double>(benchScenes(settings.size).size()) *
                    std::pow(side, 2) / 1e6 * 3.5;  // the full render, two variants, two async displays
        return work;
    }

    ExperimentOutput run(ExperimentContext& context) const override {
        const std::vector<int> sides = imageSides(context.settings.size);
        const int frames = renderCacheFrameCount(context.settings.size);
        const std::vector<RcVariant> variants = rcVariants();
        const LoadAverage loadBefore = currentLoadAverage();
        const CpuSample cpuBefore = currentCpuSample();

        ExperimentOutput out;
        out.name = name();
        out.title = title();
        std::vector<SceneRun> runs;
        for (int side : sides) {
            for (const std::string& sceneName : benchScenes(context.settings.size)) {
                std::optional<Scene> scene = benchScene(sceneName, out.caveats);
                if (scene) runs.push_back(runScene(context, *scene, sceneName, side, frames, variants, out));
            }
        }
        const CpuSample cpuAfter = currentCpuSample();
        const LoadAverage loadAfter = currentLoadAverage();
        const double othersShare = othersCpuShare(cpuBefore, cpuAfter);
        if (const std::string busy = busyMachineWarning(othersShare, loadBefore, loadAfter, cpuAfter.cpus);
            !busy.empty())
            out.caveats.push_back(busy);

        const PaperTable documents = paperRenderCache();
        const std::string lastFrameText = "frames 2–" + std::to_string(frames);

        MarkdownTable split = frameTimeTable(runs, variants);
        MarkdownTable asyncDisplay = asyncTable(runs);
        MarkdownTable quality = qualityTable(runs, variants);

        // The documents' figures beside ours.
        MarkdownTable beside = documentsBeside(runs, documents);

        // Goals, from the measured numbers.
        const std::vector<GoalCheck> goals = checkGoals(runs, variants);
        MarkdownTable goalTable({"goal", "where", "measured", "verdict"});
        for (const GoalCheck& g : goals) goalTable.addRow({g.goal, g.where, g.measured, metText(g.met)});

        // Findings: per scene and variant at the largest size, the goals, the documents.
        addSceneHeadlines(runs, variants, sides.back(), lastFrameText, out);
        for (const std::string& line : goalHeadlines(goals)) out.headlines.push_back(line);
        out.headlines.push_back(
            "render-cache documents (GPU Render Cache, GeForce 6800): reconstruction " +
            cellNumber(*documents.value("512", "ms"), 1) + " ms (" + cellNumber(*documents.value("512", "fps"), 0) +
            " fps) at 512², " + cellNumber(*documents.value("1024", "ms"), 1) + " ms (" +
            cellNumber(*documents.value("1024", "fps"), 0) + " fps) at 1024², " + paperRenderCacheCpu());
        if (std::find(sides.begin(), sides.end(), 1024) == sides.end())
            out.caveats.push_back("the 1024² goals (reconstruction ≤ " + cellNumber(kGoalReconstructionMs1024, 1) +
                                  " ms, ≥ " + cellNumber(kGoalFps, 0) +
                                  " fps end to end) are not measured at this "
                                  "size; `raycache bench render-cache --full` runs 1024²");

        // Plots.
        out.plots = writePlots(context, runs, variants, sides, frames, documents);

        std::string md = methodMarkdown(context.settings.size, sides, frames, lastFrameText);
        md += "### Frame time: reconstruction and sample generation\n\n" + split.toMarkdown() + "\n";
        md += "### Displayed at its own rate\n\n" + asyncDisplay.toMarkdown() +
              "\nThe viewer's asynchronous mode without a window (rendercache/AsyncRenderCache.h): display frames "
              "along the same path, each reconstructed for the next camera as soon as the last is done, while the "
              "tracer threads feed samples; threads split as the viewer splits them. Not included: the viewer's "
              "8-bit encoding, upload and present (benchmarks/render_cache_async_speed.sh measures them under "
              "Xvfb). Images depend on timing here, so they have no quality column.\n\n";
        md += "### Quality against the full render\n\n" + quality.toMarkdown() +
              "\nPSNR is infinite for a frame identical to the full render; such frames are counted apart and left "
              "out of the means.\n\n";
        md += "### The documents' figures and our goals beside ours\n\n" + beside.toMarkdown() + "\nThe documents (" +
              documents.source + ", " + documents.conditions + "): " + paperRenderCacheCpu() +
              ". Their time excludes sample generation; it compares with our reconstruction column, on a CPU 20 "
              "years newer.\n\n";
        md += goalTable.toMarkdown() + "\n";
        md += "Other processes used " + formatOthersShare(othersShare) +
              " of the machine's CPU time while this experiment ran. Load average (1, 5, 15 min): " +
              loadBefore.toString() + " before, " + loadAfter.toString() +
              " after (it includes the bench's own earlier work).\n\n";
        md +=
            "Last frame of each path, with difference heat maps against the full render (×1: red = totally "
            "different; ×4: red = 0.25):\n\n";
        for (const std::string& image : out.images) md += "- [" + image + "](" + image + ")\n";
        out.markdown = md;

        writeResultsJson(context, runs, variants, sides, frames, documents, goals, loadBefore, loadAfter, othersShare,
                         out.caveats);
        writeTextFileAtomically(context.dir / "results.md", experimentMarkdown(out));
        return out;
    }

private:
    // Per scene and size: the full render and each variant's frame time split.
    static MarkdownTable frameTimeTable(const std::vector<SceneRun>& runs, const std::vector<RcVariant>& variants) {
        MarkdownTable split({"scene", "size", "variant", "ms per frame", "reconstruction ms", "reprojection ms",
                             "maps ms", "filters ms", "MB counted", "GB/s", "sample generation ms", "trace ms",
                             "reshade ms", "× full render (95 % CI)", "fresh pixels", "holes", "reshaded"});
        for (const SceneRun& r : runs) {
            split.addRow({r.scene, sideText(r.side), "full render (ray pipeline)", rangeCell(afterSkipped(r.fullMs), 1),
                          "–", "–", "–", "–", "–", "–", "–", "–", "–", "1.00×", "100 %", "–", "–"});
            for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                const std::vector<FrameRecord>& f = r.variants[vi].frames;
                split.addRow(
                    {r.scene, sideText(r.side), variants[vi].label,
                     rangeCell(series(f, [](const FrameRecord& x) { return x.ms; }), 1),
                     rangeCell(series(f, [](const FrameRecord& x) { return x.rc.reconstructionMs(); }), 2),
                     rangeCell(series(f, [](const FrameRecord& x) { return x.rc.reprojectMs; }), 2),
                     rangeCell(series(f, [](const FrameRecord& x) { return x.rc.mapsMs; }), 2),
                     rangeCell(series(f, [](const FrameRecord& x) { return x.rc.filterMs; }), 2),
                     rangeCell(series(f,
                                      [](const FrameRecord& x) {
                                          return static_cast<double>(x.rc.reconstructionBytes()) / 1e6;
                                      }),
                               1),
                     rangeCell(series(f, [](const FrameRecord& x) { return x.rc.reconstructionGbPerSecond(); }), 2),
                     rangeCell(series(f, [](const FrameRecord& x) { return x.rc.sampleGenerationMs(); }), 2),
                     rangeCell(series(f, [](const FrameRecord& x) { return x.rc.traceMs; }), 2),
                     rangeCell(series(f, [](const FrameRecord& x) { return x.rc.reshadeMs; }), 2),
                     speedupCell(r.variants[vi].speedup),
                     rangeCell(series(f, [](const FrameRecord& x) { return 100.0 * x.rc.freshShare(); }), 1) + " %",
                     rangeCell(series(f, [](const FrameRecord& x) { return static_cast<double>(x.rc.holes); }), 0),
                     rangeCell(series(f, [](const FrameRecord& x) { return static_cast<double>(x.rc.reshaded); }), 0)});
            }
        }
        return split;
    }

    // Per scene and size: the asynchronous display's rate, and the full render's beside it.
    static MarkdownTable asyncTable(const std::vector<SceneRun>& runs) {
        MarkdownTable table({"scene", "size", "display", "display fps", "full render fps", "tracer Msamples/s",
                             "reconstruction ms (median)", "reshade ms (median)", "reshading: one in"});
        const std::vector<AsyncBudget> budgets = asyncBudgets();
        for (const SceneRun& r : runs) {
            const double fullMs = medianOf(afterSkipped(r.fullMs));
            for (std::size_t b = 0; b < r.async.size(); ++b) {
                const AsyncDisplayResult& a = r.async[b];
                table.addRow({r.scene, sideText(r.side), budgets[b].label, cellNumber(a.displayFps, 1),
                              fullMs > 0.0 ? cellNumber(1000.0 / fullMs, 1) : "–",
                              cellNumber(a.samplesPerSecond / 1e6, 2), cellNumber(a.medianReconstructionMs, 1),
                              cellNumber(a.medianReshadeMs, 1), std::to_string(a.lastReshadeInterval)});
            }
        }
        return table;
    }

    // Per scene, size and variant: PSNR and SSIM against the full render, and on the mirror pixels.
    static MarkdownTable qualityTable(const std::vector<SceneRun>& runs, const std::vector<RcVariant>& variants) {
        MarkdownTable quality({"scene", "size", "variant", "PSNR dB", "mean PSNR dB", "SSIM", "mirror pixels",
                               "mirror PSNR dB", "mean mirror PSNR dB"});
        for (const SceneRun& r : runs) {
            std::vector<double> mirrorShare;
            for (std::int64_t m : r.mirrorPixels)
                mirrorShare.push_back(100.0 * static_cast<double>(m) / (static_cast<double>(r.side) * r.side));
            for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                const std::vector<FrameRecord>& f = r.variants[vi].frames;
                const std::vector<double> peak = series(f, [](const FrameRecord& x) { return x.metrics.psnr; });
                const std::vector<double> mirror = series(f, [](const FrameRecord& x) { return x.mirrorPsnr; });
                quality.addRow({r.scene, sideText(r.side), variants[vi].label, psnrCell(peak),
                                cellNumber(mean(finiteOnly(peak)), 2),
                                rangeCell(series(f, [](const FrameRecord& x) { return x.metrics.ssim; }), 4),
                                rangeCell(afterSkipped(mirrorShare), 1) + " %", psnrCell(mirror),
                                cellNumber(mean(finiteOnly(mirror)), 2)});
            }
        }
        return quality;
    }

    // The documents' GPU figures, our goals and our medians side by side, per size.
    static MarkdownTable documentsBeside(const std::vector<SceneRun>& runs, const PaperTable& documents) {
        MarkdownTable beside({"size", "documents: reconstruction, GPU (GeForce 6800)", "goal: reconstruction",
                              "raycache: reconstruction ms, median (Render Cache / + re-evaluated reflections)",
                              "raycache: whole frame ms, median (Render Cache / + re-evaluated reflections)",
                              "raycache: full render ms, median"});
        for (int side : {512, 1024}) {
            const std::optional<double> fps = documents.value(std::to_string(side), "fps");
            const std::optional<double> ms = documents.value(std::to_string(side), "ms");
            std::string ours, whole, full;
            for (const SceneRun& r : runs) {
                if (r.side != side) continue;
                const auto med = [&](std::size_t vi, auto get) { return medianOf(series(r.variants[vi].frames, get)); };
                const auto rec = [](const FrameRecord& x) { return x.rc.reconstructionMs(); };
                const auto total = [](const FrameRecord& x) { return x.ms; };
                ours += (ours.empty() ? "" : "; ") + r.scene + " " + cellNumber(med(0, rec), 2) + " / " +
                        cellNumber(med(1, rec), 2);
                whole += (whole.empty() ? "" : "; ") + r.scene + " " + cellNumber(med(0, total), 1) + " / " +
                         cellNumber(med(1, total), 1);
                full += (full.empty() ? "" : "; ") + r.scene + " " + cellNumber(medianOf(afterSkipped(r.fullMs)), 1);
            }
            const double goal = side == 512 ? kGoalReconstructionMs512 : kGoalReconstructionMs1024;
            beside.addRow({sideText(side), cellNumber(*fps, 0) + " fps (" + cellNumber(*ms, 1) + " ms)",
                           "≤ " + cellNumber(goal, 1) + " ms", ours.empty() ? "not run at this size" : ours,
                           whole.empty() ? "not run at this size" : whole,
                           full.empty() ? "not run at this size" : full});
        }

        return beside;
    }

    // One headline per scene and variant at `side`.
    static void addSceneHeadlines(const std::vector<SceneRun>& runs, const std::vector<RcVariant>& variants, int side,
                                  const std::string& lastFrameText, ExperimentOutput& out) {
        for (const SceneRun& r : runs) {
            if (r.side != side) continue;
            for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                const std::vector<FrameRecord>& f = r.variants[vi].frames;
                out.headlines.push_back(
                    "render-cache " + r.scene + " " + sideText(r.side) + " " + variants[vi].label + ": " +
                    cellNumber(medianOf(series(f, [](const FrameRecord& x) { return x.ms; })), 1) +
                    " ms per frame (median), full render " + cellNumber(medianOf(afterSkipped(r.fullMs)), 1) +
                    " ms: " + describeSpeedup(r.variants[vi].speedup) + "; reconstruction " +
                    cellNumber(medianOf(series(f, [](const FrameRecord& x) { return x.rc.reconstructionMs(); })), 2) +
                    " ms + sample generation " +
                    cellNumber(medianOf(series(f, [](const FrameRecord& x) { return x.rc.sampleGenerationMs(); })), 2) +
                    " ms; mean PSNR " +
                    cellNumber(mean(finiteOnly(series(f, [](const FrameRecord& x) { return x.metrics.psnr; }))), 2) +
                    " dB, mirror pixels " +
                    cellNumber(mean(finiteOnly(series(f, [](const FrameRecord& x) { return x.mirrorPsnr; }))), 2) +
                    " dB; " +
                    cellNumber(medianOf(series(f, [](const FrameRecord& x) { return 100.0 * x.rc.freshShare(); })), 1) +
                    " % of pixels fresh (" + lastFrameText + ")");
            }
        }
    }

    // What the experiment does and how to read its tables.
    static std::string methodMarkdown(BenchSize size, const std::vector<int>& sides, int frames,
                                      const std::string& lastFrameText) {
        const RenderCacheSettings rcDefaults;
        std::string md = "Each scene's own camera path — " + sceneNamesListed(benchScenes(size), "`") + " — for " +
                         std::to_string(frames) + " frames at ";
        for (std::size_t i = 0; i < sides.size(); ++i)
            md += (i ? " and " : "") + std::to_string(sides[i]) + "x" + std::to_string(sides[i]);
        md +=
            " pixels, the scenes' own caching (CCT on their mirrors and glass), caches and Render Cache starting "
            "empty. Every frame is rendered in turn by three sessions sharing one tracer and its threads, so "
            "machine noise hits them alike: the **full render** (the ray pipeline: the reference image and the "
            "speed baseline), the **Render Cache** (a reprojected sample keeps the colour it was traced with, as "
            "in the 2002 Render Cache) and the **Render Cache + re-evaluated reflections** (highlights and "
            "reflected/refracted colour of reprojected mirror, glass and glossy samples shaded again from the "
            "new eye, their rays answered by the caching cubes where they can). Both Render Cache variants trace "
            "the same primary rays: a budget of " +
            cellNumber(100.0 * rcDefaults.budget, 0) +
            " % of the pixels per frame (α = " + cellNumber(rcDefaults.alpha, 2) + ", " +
            cellNumber(100.0 * rcDefaults.predictShare, 0) +
            " % of it through the predicted next camera, samples evicted after " + std::to_string(rcDefaults.maxAge) +
            " reprojections); re-evaluating reflections adds secondary rays, not primary ones.\n\n"
            "**Frame 1 traces every pixel** (there are no samples yet, so its image equals the full render's): "
            "it is left out of every median, mean, range and speed-up below, and kept in results.json. "
            "*Reconstruction* = reprojection (aging, eviction, projection, depth test) + maps (depth culling, "
            "hole detection, priority and request maps, prediction maps) + filters (3x3 filter, 7x7 prefilter, "
            "writing the image); *MB counted*: the bytes reconstruction's passes read and write, counted from "
            "their record sizes and the frame's counts (rendercache/ReconstructionBytes.h: a model, not measured "
            "memory traffic; 1 MB = 10^6 bytes), and *GB/s* those bytes over the reconstruction time; "
            "*sample generation* = tracing the requested pixels (this frame's camera and the "
            "predicted one, with the merge of the caches' stores) + reshading. *Mirror pixels*: pixels whose "
            "first hit in the full render is an object that reflects (mirrors, and glass, which reflects "
            "10 %), found by tracing the full render's primary rays. Speed-ups: mean time per frame of the full "
            "render over the variant's along the path, 95 % CI from the paired bootstrap over the frames "
            "(bench/SpeedupInterval). Cells are median (min–max) over " +
            lastFrameText + ".\n\n";
        return md;
    }

    SceneRun runScene(ExperimentContext& context, const Scene& scene, const std::string& sceneName, int side,
                      int frames, const std::vector<RcVariant>& variants, ExperimentOutput& out) const {
        const TraceScene tracer(scene);
        const double mp = static_cast<double>(side) * side / 1e6;
        context.progress.step("render-cache: " + sceneName + " " + sideText(side) + ", " + std::to_string(frames) +
                              " frames");

        RenderSettings fullSettings;
        fullSettings.width = fullSettings.height = side;
        fullSettings.threads = context.settings.threads;
        fullSettings.pipeline = PipelineKind::Ray;
        RenderSession full(scene, fullSettings, tracer, context.parallel);
        std::vector<std::unique_ptr<RenderSession>> sessions;
        for (const RcVariant& v : variants) {
            RenderSettings s = fullSettings;
            s.pipeline = PipelineKind::RenderCache;
            s.renderCache.reflections = v.reflections;
            sessions.push_back(std::make_unique<RenderSession>(scene, s, tracer, context.parallel));
        }

        SceneRun run;
        run.scene = sceneName;
        run.side = side;
        run.variants.resize(variants.size());
        Image reference;
        std::vector<Image> images(variants.size());
        const auto millisecondsSince = [](std::chrono::steady_clock::time_point start) {
            return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        };
        for (int f = 0; f < frames; ++f) {
            const Camera camera = scene.cameraPath.cameraAt(scene.camera, f);
            // The timed renders back to back, the metrics after them.
            auto start = std::chrono::steady_clock::now();
            full.render(camera, reference);
            run.fullMs.push_back(millisecondsSince(start));
            context.progress.advance(mp);
            for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                start = std::chrono::steady_clock::now();
                const FrameStats stats = sessions[vi]->render(camera, images[vi]);
                FrameRecord record;
                record.ms = millisecondsSince(start);
                if (!stats.renderCache) throw RuntimeError("the Render Cache pipeline returned no statistics");
                record.rc = *stats.renderCache;
                run.variants[vi].frames.push_back(record);
                context.progress.advance(0.5 * mp);
            }
            const std::vector<unsigned char> mask = mirrorMask(scene, tracer, camera, side, context.parallel);
            run.mirrorPixels.push_back(std::count(mask.begin(), mask.end(), static_cast<unsigned char>(1)));
            for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                FrameRecord& record = run.variants[vi].frames.back();
                record.metrics = compareImages(images[vi], reference);
                record.mirrorPsnr = maskedPsnr(images[vi], reference, mask);
            }
            context.progress.advance(0.5 * mp);
        }

        // The asynchronous display along the same path, after the timed
        // synchronous frames, on a session of its own (its caching cubes).
        for (const AsyncBudget& budget : asyncBudgets()) {
            RenderSettings s = fullSettings;
            s.pipeline = PipelineKind::RenderCache;
            RenderSession session(scene, s, tracer, context.parallel);
            run.async.push_back(measureAsyncDisplay(scene, tracer, s, &session.cache(), frames - 1, budget.reshadeMs));
            context.progress.advance(0.5 * mp * frames);
        }

        BootstrapSettings bootstrap;
        bootstrap.statistic = TimeStatistic::Mean;  // a path: frames differ by design
        for (VariantRun& v : run.variants)
            v.speedup = bootstrapSpeedup(afterSkipped(run.fullMs),
                                         series(v.frames, [](const FrameRecord& x) { return x.ms; }), bootstrap);

        // The last frame's images and heat maps.
        const std::string stem = sceneName + "-" + std::to_string(side);
        writeImage(reference, context.dir / (stem + "-full.png"));
        out.images.push_back(stem + "-full.png");
        for (std::size_t vi = 0; vi < variants.size(); ++vi) {
            const std::string s = stem + "-" + variants[vi].key;
            writeImage(images[vi], context.dir / (s + ".png"));
            writeImage(renderHeatmap(images[vi], reference, {1.0}), context.dir / (s + "-heatmap.png"));
            writeImage(renderHeatmap(images[vi], reference, {0.25}), context.dir / (s + "-heatmap-x4.png"));
            out.images.insert(out.images.end(), {s + ".png", s + "-heatmap.png", s + "-heatmap-x4.png"});
        }
        return run;
    }

    static std::vector<GoalCheck> checkGoals(const std::vector<SceneRun>& runs,
                                             const std::vector<RcVariant>& variants) {
        std::vector<GoalCheck> goals;
        const auto reconstruction = [](const FrameRecord& x) { return x.rc.reconstructionMs(); };
        for (int side : {512, 1024}) {
            const double target = side == 512 ? kGoalReconstructionMs512 : kGoalReconstructionMs1024;
            const std::string goal =
                "reconstruction ≤ " + cellNumber(target, 1) + " ms at " + sideText(side) + " (median)";
            bool any = false;
            for (const SceneRun& r : runs) {
                if (r.side != side) continue;
                for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                    any = true;
                    const double ms = medianOf(series(r.variants[vi].frames, reconstruction));
                    goals.push_back({goal, r.scene + ", " + variants[vi].label, cellNumber(ms, 2) + " ms",
                                     std::isfinite(ms) ? std::optional<bool>(ms <= target) : std::nullopt});
                }
            }
            if (!any) goals.push_back({goal, "every scene", "not run at this size", std::nullopt});
        }
        {
            const std::string goal = "end to end ≥ " + cellNumber(kGoalFps, 0) + " fps (mean frame time) with mean " +
                                     "PSNR ≥ " + cellNumber(kGoalMeanPsnr, 0) + " dB at " + sideText(kGoalFpsSide);
            bool any = false;
            for (const SceneRun& r : runs) {
                if (r.side != kGoalFpsSide || std::find(kEndToEndGoalScenes.begin(), kEndToEndGoalScenes.end(),
                                                        r.scene) == kEndToEndGoalScenes.end())
                    continue;
                for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                    any = true;
                    const std::vector<FrameRecord>& f = r.variants[vi].frames;
                    const double fps = 1000.0 / mean(series(f, [](const FrameRecord& x) { return x.ms; }));
                    const double peak =
                        mean(finiteOnly(series(f, [](const FrameRecord& x) { return x.metrics.psnr; })));
                    std::optional<bool> met;
                    if (std::isfinite(fps)) met = fps >= kGoalFps && (!std::isfinite(peak) || peak >= kGoalMeanPsnr);
                    goals.push_back({goal, r.scene + ", " + variants[vi].label,
                                     cellNumber(fps, 1) + " fps, mean PSNR " + cellNumber(peak, 2) + " dB", met});
                }
            }
            if (!any) goals.push_back({goal, "room, behind-32", "not run at this size", std::nullopt});
        }
        {
            const std::string goal = "re-evaluated reflections ≥ " + cellNumber(kGoalMirrorGainDb, 0) +
                                     " dB better than the Render Cache on mirror pixels (mean PSNR, same budget)";
            for (const SceneRun& r : runs) {
                const auto mirror = [](const FrameRecord& x) { return x.mirrorPsnr; };
                const double plain = mean(finiteOnly(series(r.variants[0].frames, mirror)));
                const double reshaded = mean(finiteOnly(series(r.variants[1].frames, mirror)));
                const double gain = reshaded - plain;
                goals.push_back(
                    {goal, r.scene + " " + sideText(r.side),
                     cellNumber(gain, 2) + " dB (" + cellNumber(reshaded, 2) + " vs " + cellNumber(plain, 2) + " dB)",
                     std::isfinite(gain) ? std::optional<bool>(gain >= kGoalMirrorGainDb) : std::nullopt});
            }
        }
        return goals;
    }

    // One line per goal: in how many places it was met.
    static std::vector<std::string> goalHeadlines(const std::vector<GoalCheck>& goals) {
        std::vector<std::string> lines;
        for (std::size_t i = 0; i < goals.size();) {
            std::size_t j = i;
            int measured = 0, met = 0;
            std::string missed;
            for (; j < goals.size() && goals[j].goal == goals[i].goal; ++j) {
                if (!goals[j].met) continue;
                ++measured;
                if (*goals[j].met)
                    ++met;
                else
                    missed += (missed.empty() ? "" : "; ") + goals[j].where + " " + goals[j].measured;
            }
            std::string line = "render-cache goal, " + goals[i].goal + ": ";
            if (measured == 0)
                line += "not measured at this size";
            else if (met == measured)
                line += "met (" + std::to_string(met) + " of " + std::to_string(measured) + ")";
            else
                line += "not met (met in " + std::to_string(met) + " of " + std::to_string(measured) +
                        "; missed: " + missed + ")";
            lines.push_back(line);
            i = j;
        }
        return lines;
    }

    static std::vector<std::string> writePlots(ExperimentContext& context, const std::vector<SceneRun>& runs,
                                               const std::vector<RcVariant>& variants, const std::vector<int>& sides,
                                               int frames, const PaperTable& documents) {
        std::vector<std::string> files;
        for (int side : sides) {
            SvgPlot psnrPlot, mirrorPlot, freshPlot;
            psnrPlot.title = "render-cache " + sideText(side) + ": PSNR per frame against the full render";
            psnrPlot.yLabel = "PSNR (dB)";
            psnrPlot.referenceY = kGoalMeanPsnr;
            mirrorPlot.title = "render-cache " + sideText(side) + ": PSNR of mirror pixels per frame";
            mirrorPlot.yLabel = "mirror-pixel PSNR (dB)";
            freshPlot.title = "render-cache " + sideText(side) + ": pixels from fresh samples (frames 2–" +
                              std::to_string(frames) + "; frame 1 traces all)";
            freshPlot.yLabel = "fresh pixels (%)";
            for (SvgPlot* p : {&psnrPlot, &mirrorPlot, &freshPlot}) p->xLabel = "frame";
            for (const SceneRun& r : runs) {
                if (r.side != side) continue;
                for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                    const std::string label = r.scene + ", " + variants[vi].label;
                    PlotSeries psnrSeries{label, {}}, mirrorSeries{label, {}}, freshSeries{label, {}};
                    psnrSeries.dashed = mirrorSeries.dashed = freshSeries.dashed = vi == 0;
                    const std::vector<FrameRecord>& f = r.variants[vi].frames;
                    for (std::size_t k = 0; k < f.size(); ++k) {
                        const double x = static_cast<double>(k + 1);
                        psnrSeries.points.push_back({x, f[k].metrics.psnr});  // infinite (identical) frames are skipped
                        mirrorSeries.points.push_back({x, f[k].mirrorPsnr});
                        if (k >= kSkippedFrames || f.size() <= kSkippedFrames)
                            freshSeries.points.push_back({x, 100.0 * f[k].rc.freshShare()});
                    }
                    psnrPlot.series.push_back(std::move(psnrSeries));
                    mirrorPlot.series.push_back(std::move(mirrorSeries));
                    freshPlot.series.push_back(std::move(freshSeries));
                }
            }
            const std::string s = std::to_string(side);
            writeSvgPlot(psnrPlot, (context.dir / ("psnr-per-frame-" + s + ".svg")).string());
            writeSvgPlot(mirrorPlot, (context.dir / ("mirror-psnr-per-frame-" + s + ".svg")).string());
            writeSvgPlot(freshPlot, (context.dir / ("fresh-pixels-per-frame-" + s + ".svg")).string());
            files.insert(files.end(), {"psnr-per-frame-" + s + ".svg", "mirror-psnr-per-frame-" + s + ".svg",
                                       "fresh-pixels-per-frame-" + s + ".svg"});
        }

        // Where the time goes: median per scene, size and variant, whiskers min–max.
        SvgPlot splitPlot;
        splitPlot.title =
            "render-cache: frame time split (median, whiskers min–max, frames 2–" + std::to_string(frames) + ")";
        splitPlot.yLabel = "ms per frame";
        splitPlot.bars = true;
        PlotSeries reconstruction{"reconstruction", {}}, generation{"sample generation", {}}, whole{"whole frame", {}},
            fullRender{"full render (ray pipeline)", {}}, docs{"documents: GPU reconstruction (GeForce 6800)", {}};
        docs.dashed = true;
        const auto point = [](double x, const std::vector<double>& values) {
            const std::vector<double> finite = finiteOnly(values);
            if (finite.empty()) return PlotPoint{x, std::nan(""), std::nullopt, std::nullopt};
            const SampleSummary s = summarize(finite);
            return PlotPoint{x, s.median, s.min, s.max};
        };
        for (const SceneRun& r : runs) {
            for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                const double x = static_cast<double>(splitPlot.categories.size());
                splitPlot.categories.push_back(r.scene + " " + sideText(r.side) + " " + variants[vi].key);
                const std::vector<FrameRecord>& f = r.variants[vi].frames;
                reconstruction.points.push_back(
                    point(x, series(f, [](const FrameRecord& y) { return y.rc.reconstructionMs(); })));
                generation.points.push_back(
                    point(x, series(f, [](const FrameRecord& y) { return y.rc.sampleGenerationMs(); })));
                whole.points.push_back(point(x, series(f, [](const FrameRecord& y) { return y.ms; })));
                fullRender.points.push_back(point(x, afterSkipped(r.fullMs)));
                docs.points.push_back({x, documents.value(std::to_string(r.side), "ms").value_or(std::nan(""))});
            }
        }
        splitPlot.series = {reconstruction, generation, whole, fullRender, docs};
        splitPlot.width = std::max(860, 130 * static_cast<int>(splitPlot.categories.size()));
        splitPlot.height = 480;
        writeSvgPlot(splitPlot, (context.dir / "frame-time-split.svg").string());
        files.push_back("frame-time-split.svg");
        return files;
    }

    void writeResultsJson(ExperimentContext& context, const std::vector<SceneRun>& runs,
                          const std::vector<RcVariant>& variants, const std::vector<int>& sides, int frames,
                          const PaperTable& documents, const std::vector<GoalCheck>& goals,
                          const LoadAverage& loadBefore, const LoadAverage& loadAfter, double othersShare,
                          const std::vector<std::string>& caveats) const {
        const RenderCacheSettings rc;
        nlohmann::json variantsSpec = nlohmann::json::array();
        for (const RcVariant& v : variants)
            variantsSpec.push_back(
                {{"key", v.key}, {"label", v.label}, {"reflections", reprojectedReflectionsName(v.reflections)}});
        nlohmann::json runsJson = nlohmann::json::array();
        for (const SceneRun& r : runs) {
            nlohmann::json variantsJson = nlohmann::json::object();
            for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                const std::vector<FrameRecord>& f = r.variants[vi].frames;
                nlohmann::json perFrame = nlohmann::json::array();
                for (std::size_t k = 0; k < f.size(); ++k)
                    perFrame.push_back(frameJson(static_cast<int>(k + 1), f[k], r.mirrorPixels[k]));
                const auto get = [&](auto g) { return summaryJson(series(f, g)); };
                variantsJson[variants[vi].key] = {
                    {"label", variants[vi].label},
                    {"frames", perFrame},
                    {"speedup_vs_full", toJson(r.variants[vi].speedup)},
                    {"summary",
                     {{"ms", get([](const FrameRecord& x) { return x.ms; })},
                      {"reconstruction_ms", get([](const FrameRecord& x) { return x.rc.reconstructionMs(); })},
                      {"reproject_ms", get([](const FrameRecord& x) { return x.rc.reprojectMs; })},
                      {"maps_ms", get([](const FrameRecord& x) { return x.rc.mapsMs; })},
                      {"filter_ms", get([](const FrameRecord& x) { return x.rc.filterMs; })},
                      {"reconstruction_counted_bytes",
                       get([](const FrameRecord& x) { return static_cast<double>(x.rc.reconstructionBytes()); })},
                      {"reconstruction_gb_per_s",
                       get([](const FrameRecord& x) { return x.rc.reconstructionGbPerSecond(); })},
                      {"sample_generation_ms", get([](const FrameRecord& x) { return x.rc.sampleGenerationMs(); })},
                      {"trace_ms", get([](const FrameRecord& x) { return x.rc.traceMs; })},
                      {"reshade_ms", get([](const FrameRecord& x) { return x.rc.reshadeMs; })},
                      {"fresh_share", get([](const FrameRecord& x) { return x.rc.freshShare(); })},
                      {"holes", get([](const FrameRecord& x) { return static_cast<double>(x.rc.holes); })},
                      {"reshaded", get([](const FrameRecord& x) { return static_cast<double>(x.rc.reshaded); })},
                      {"psnr_db", get([](const FrameRecord& x) { return x.metrics.psnr; })},
                      {"ssim", get([](const FrameRecord& x) { return x.metrics.ssim; })},
                      {"mae", get([](const FrameRecord& x) { return x.metrics.mae; })},
                      {"mirror_psnr_db", get([](const FrameRecord& x) { return x.mirrorPsnr; })}}}};
            }
            nlohmann::json asyncJson = nlohmann::json::object();
            const std::vector<AsyncBudget> budgets = asyncBudgets();
            for (std::size_t b = 0; b < r.async.size(); ++b) {
                const AsyncDisplayResult& a = r.async[b];
                asyncJson[budgets[b].key] = {{"label", budgets[b].label},
                                             {"reshade_budget_ms", budgets[b].reshadeMs},
                                             {"display_frames", a.displayFrames},
                                             {"display_fps", a.displayFps},
                                             {"tracer_samples_per_s", a.samplesPerSecond},
                                             {"median_reconstruction_ms", a.medianReconstructionMs},
                                             {"median_reshade_ms", a.medianReshadeMs},
                                             {"last_reshade_interval", a.lastReshadeInterval}};
            }
            runsJson.push_back(
                {{"scene", r.scene},
                 {"width", r.side},
                 {"height", r.side},
                 {"full", {{"frame_ms", r.fullMs}, {"summary", {{"ms", summaryJson(afterSkipped(r.fullMs))}}}}},
                 {"mirror_pixels", r.mirrorPixels},
                 {"variants", variantsJson},
                 {"async", asyncJson}});
        }
        nlohmann::json goalsJson = nlohmann::json::array();
        for (const GoalCheck& g : goals)
            goalsJson.push_back({{"goal", g.goal},
                                 {"where", g.where},
                                 {"measured", g.measured},
                                 {"met", g.met ? nlohmann::json(*g.met) : nlohmann::json()}});
        nlohmann::json docs = toJson(documents);
        docs["cpu"] = paperRenderCacheCpu();
        const nlohmann::json othersJson = othersShare >= 0.0 ? nlohmann::json(othersShare) : nlohmann::json();
        writeJsonFile(context.dir / "results.json",
                      {{"experiment", name()},
                       {"title", title()},
                       {"size", toString(context.settings.size)},
                       {"settings",
                        {{"scenes", benchScenes(context.settings.size)},
                         {"sides", sides},
                         {"frames", frames},
                         {"skipped_frames", kSkippedFrames},
                         {"technique", "scene materials (CCT on mirrors and glass)"},
                         {"baseline", "full render, ray pipeline"},
                         {"variants", variantsSpec},
                         {"render_cache",
                          {{"budget", rc.budget},
                           {"alpha", rc.alpha},
                           {"max_age", rc.maxAge},
                           {"predict_share", rc.predictShare},
                           {"margin", rc.margin},
                           {"depth_cull_threshold", rc.depthCullThreshold},
                           {"request_tile_size", rc.requestTileSize},
                           {"refresh_all_hole_share", rc.refreshAllHoleShare},
                           {"seed", rc.seed}}},
                         {"max_depth", RenderSettings{}.maxDepth},
                         {"bootstrap",
                          {{"resamples", BootstrapSettings{}.resamples},
                           {"seed", BootstrapSettings{}.seed},
                           {"confidence", BootstrapSettings{}.confidence},
                           {"statistic", "mean"}}}}},
                       {"environment", toJson(context.environment)},
                       {"documents", docs},
                       {"goal_targets",
                        {{"reconstruction_ms_512", kGoalReconstructionMs512},
                         {"reconstruction_ms_1024", kGoalReconstructionMs1024},
                         {"end_to_end_fps", kGoalFps},
                         {"end_to_end_side", kGoalFpsSide},
                         {"end_to_end_scenes", kEndToEndGoalScenes},
                         {"mean_psnr_db", kGoalMeanPsnr},
                         {"mirror_gain_db", kGoalMirrorGainDb}}},
                       {"goals", goalsJson},
                       {"load_average", {{"before", loadBefore.toString()}, {"after", loadAfter.toString()}}},
                       {"others_cpu_share", othersJson},
                       {"caveats", caveats},
                       {"runs", runsJson}});
    }
};

}  // namespace

std::unique_ptr<Experiment> makeRenderCacheExperiment() {
    return std::make_unique<RenderCacheExperiment>();
}

}  // namespace raycache
