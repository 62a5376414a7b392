#include "bench/FillRateExperiment.h"

#include <cmath>

#include "bench/MarkdownTable.h"
#include "bench/PaperFigures.h"
#include "bench/ResultsJson.h"
#include "bench/SvgPlot.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "scene/BuiltinScenes.h"
#include "session/FrameLoop.h"

namespace raycache {

namespace {

constexpr int kSteps = 9;  // camera moves after the first frame
constexpr float kDegreesPerStep = 10.0f / 3.0f;
constexpr int kFillRateResolutions[] = {128, 256, 512};

// Multi-resolution cubes (docs/caching.md) at the finest resolution: the
// share of lookups traced per frame, beside one level. The goal for
// this protocol: at most 5 % traced after frame 2.
constexpr int kMultiResolutionFaces = 512;
constexpr int kFillRateLevels = 4;
constexpr float kErrorBounds[] = {0.25f, 1.0f};

int fillRateImageSide(BenchSize size) {
    return size == BenchSize::Tiny ? 48 : 1024;
}

int mainObjectId(const Scene& scene) {
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].name == "main") return static_cast<int>(i);
    throw RuntimeError("behind-0 has no object named main");
}

// Lookups a frame traced (not answered by a cube), % of its lookups.
double tracedPercent(const FrameCacheStats& c) {
    return c.lookups() ? 100.0 - 100.0 * static_cast<double>(c.hits()) / static_cast<double>(c.lookups()) : 100.0;
}

// What every run of the experiment shares: the scene, the camera's orbit
// around the main sphere, the image size.
struct FillRatePath {
    ExperimentContext& context;
    Scene scene;
    CameraPath path;
    int side = 0;
    double frameWork = 0.0;  // progress per frame rendered

    explicit FillRatePath(ExperimentContext& c) : context(c), side(fillRateImageSide(c.settings.size)) {
        frameWork = static_cast<double>(side) * side / 1e6 * 1.3;
        std::optional<Scene> builtin = makeBuiltinScene("behind-0");
        if (!builtin) throw RuntimeError("built-in scene behind-0 is missing");
        scene = std::move(*builtin);
        path.kind = CameraPathKind::Orbit;
        path.center = scene.camera.lookAt;  // the main sphere's centre
        path.degreesPerFrame = kDegreesPerStep;
    }
    // CCT at `resolution`, every other setting the experiment's.
    RenderSettings cctSettings(int resolution) const {
        RenderSettings settings;
        settings.width = settings.height = side;
        settings.threads = context.settings.threads;
        settings.cache.techniqueOverride = CacheTechnique::Cct;
        settings.cache.resolutionOverride = resolution;
        return settings;
    }
    // Renders the path's frames with `settings`, calling onFrame after each.
    void render(const RenderSettings& settings, const FrameCallback& onFrame) const {
        renderFrames(scene, path, settings, kSteps + 1, [&](const FrameResult& r, const Image& film, const RayCache& caches) {
            onFrame(r, film, caches);
            context.progress.advance(frameWork);
        });
    }
};

// What the runs measured, per frame of the path.
struct FillRateMeasurements {
    // One level at each of kFillRateResolutions: invalid % after k frames (k = 0..10).
    std::vector<std::vector<double>> invalid;
    nlohmann::json series = nlohmann::json::array();
    std::vector<PlotSeries> invalidSeries;
    // Lookups traced per frame (%) at kMultiResolutionFaces: one level, each of
    // kErrorBounds with kFillRateLevels levels, resolution from the view (with
    // the faces it chose), visible-surface fill.
    std::vector<double> plainTraced;
    std::vector<std::vector<double>> levelsTraced;
    nlohmann::json multiResolution = nlohmann::json::array();
    std::vector<double> viewTraced, fillTraced;
    std::vector<int> viewSizes;
};

void measureOneLevel(const FillRatePath& orbit, FillRateMeasurements& m) {
    for (int resolution : kFillRateResolutions) {
        orbit.context.progress.step("fill-rate: " + std::to_string(resolution) + "² faces");
        std::vector<double> before, ms, hits;
        double afterLast = 100.0;
        orbit.render(orbit.cctSettings(resolution), [&](const FrameResult& r, const Image&, const RayCache& caches) {
            const FrameCacheStats& c = *r.stats.cache;
            before.push_back(c.invalidPercentBefore());
            ms.push_back(r.milliseconds);
            hits.push_back(c.lookups() ? 100.0 * static_cast<double>(c.hits()) / static_cast<double>(c.lookups())
                                       : 0.0);
            const CachingCube& cube = caches.cube(mainObjectId(orbit.scene));
            afterLast = 100.0 * static_cast<double>(cube.texelCount() - cube.validCount()) /
                        static_cast<double>(cube.texelCount());
        });
        std::vector<double> after(before.begin(), before.end());
        after.push_back(afterLast);  // after k frames, k = 0..10
        if (resolution == kMultiResolutionFaces)
            for (const double h : hits) m.plainTraced.push_back(100.0 - h);
        m.invalid.push_back(after);
        m.series.push_back({{"resolution", resolution},
                            {"invalid_percent_before_frame", before},
                            {"invalid_percent_after_last_frame", afterLast},
                            {"frame_ms", ms},
                            {"hit_percent", hits}});
        PlotSeries s{"raycache " + std::to_string(resolution) + "²", {}};
        for (std::size_t k = 0; k < after.size(); ++k) s.points.push_back({static_cast<double>(k), after[k]});
        m.invalidSeries.push_back(std::move(s));
    }
}

// The same path with multi-resolution cubes: lookups traced per frame.
void measureMultiResolution(const FillRatePath& orbit, FillRateMeasurements& m) {
    for (const float bound : kErrorBounds) {
        orbit.context.progress.step("fill-rate: " + std::to_string(kMultiResolutionFaces) + "² faces, " +
                                  std::to_string(kFillRateLevels) + " levels, bound " + cellNumber(bound, 2));
        RenderSettings settings = orbit.cctSettings(kMultiResolutionFaces);
        settings.cache.cubeLevels = kFillRateLevels;
        settings.cache.levelErrorBound = bound;
        std::vector<double> traced;
        orbit.render(settings, [&](const FrameResult& r, const Image&, const RayCache&) {
            traced.push_back(tracedPercent(*r.stats.cache));
        });
        m.multiResolution.push_back({{"faces", kMultiResolutionFaces},
                                     {"levels", kFillRateLevels},
                                     {"error_bound", bound},
                                     {"traced_percent", traced}});
        m.levelsTraced.push_back(std::move(traced));
    }
}

// The same path with the cube's resolution from the view (asked
// kMultiResolutionFaces, one level, the default error bound), and with
// texels also filled from the surfaces the camera sees (exact fill).
void measureFromViewAndFill(const FillRatePath& orbit, FillRateMeasurements& m) {
    orbit.context.progress.step("fill-rate: resolution from the view, visible-surface fill");
    for (const bool fill : {false, true}) {
        RenderSettings settings = orbit.cctSettings(kMultiResolutionFaces);
        settings.cache.resolutionFromView = !fill;
        settings.cache.visibleFill = fill ? VisibleFill::Exact : VisibleFill::Off;
        orbit.render(settings, [&](const FrameResult& r, const Image&, const RayCache& caches) {
            (fill ? m.fillTraced : m.viewTraced).push_back(tracedPercent(*r.stats.cache));
            if (!fill) m.viewSizes.push_back(caches.cube(mainObjectId(orbit.scene)).size());
        });
    }
}

void writeInvalidTexelsPlot(const FillRateMeasurements& m, const PaperTable& documents,
                            const std::filesystem::path& dir) {
    SvgPlot plot;
    plot.title = "fill-rate: invalid texels after each frame (camera moving 10/3° per frame)";
    plot.xLabel = "frames rendered";
    plot.yLabel = "invalid texels (%)";
    plot.yMin = 0.0;
    plot.yMax = 100.0;
    plot.series = m.invalidSeries;
    PlotSeries docs{"documents, after frame 1 (Fig 5.9)", {}};
    docs.line = false;
    docs.dashed = true;
    for (int resolution : kFillRateResolutions)
        docs.points.push_back({1.0, documents.value(std::to_string(resolution), "invalid-after-frame-1").value()});
    plot.series.push_back(std::move(docs));
    writeSvgPlot(plot, (dir / "invalid-texels.svg").string());
}

// results.md's body; the findings go to out.headlines.
std::string fillRateMarkdown(const FillRateMeasurements& m, const PaperTable& documents, int side,
                             ExperimentOutput& out) {
    std::string md = "behind-0's main mirror sphere in front of the camera, " + std::to_string(side) + "x" +
                     std::to_string(side) +
                     " pixels; the camera orbits the sphere's centre by 10/3° per frame (frame 1 "
                     "plus 9 steps, 30° in all), caches starting empty. Invalid texels of the sphere's cube after "
                     "each frame (= before the next).\n\n";
    MarkdownTable first({"face resolution", "documents: invalid after frame 1", "raycache: invalid after frame 1",
                         "raycache: after frame 5", "raycache: after frame 10"});
    const auto& invalid = m.invalid;
    for (std::size_t i = 0; i < std::size(kFillRateResolutions); ++i) {
        const std::string res = std::to_string(kFillRateResolutions[i]);
        first.addRow({res + "²", cellNumber(documents.value(res, "invalid-after-frame-1").value(), 0) + "%",
                      cellNumber(invalid[i][1], 1) + "%", cellNumber(invalid[i][5], 1) + "%",
                      cellNumber(invalid[i][10], 1) + "%"});
        out.headlines.push_back("fill-rate " + res + "²: " + cellNumber(invalid[i][1], 1) +
                                "% invalid after frame 1 (documents " +
                                cellNumber(documents.value(res, "invalid-after-frame-1").value(), 0) + "%), " +
                                cellNumber(invalid[i][10], 1) + "% after frame 10");
    }
    md += first.toMarkdown() + "\nThe documents: " + paperFigure59Later() + ".\n\n";
    MarkdownTable all({"frames rendered", "128²", "256²", "512²"});
    for (std::size_t k = 0; k < invalid[0].size(); ++k)
        all.addRow({std::to_string(k), cellNumber(invalid[0][k], 1) + "%", cellNumber(invalid[1][k], 1) + "%",
                    cellNumber(invalid[2][k], 1) + "%"});
    md += "Invalid texels after each frame:\n\n" + all.toMarkdown();
    MarkdownTable traced({"frame", "1 level", "4 levels, bound 0.25", "4 levels, bound 1",
                          "from the view, bound 0.25 (faces after the frame)", "visible-surface fill (exact)"});
    for (std::size_t k = 0; k < m.plainTraced.size(); ++k)
        traced.addRow({std::to_string(k + 1), cellNumber(m.plainTraced[k], 1) + "%",
                       cellNumber(m.levelsTraced[0][k], 1) + "%", cellNumber(m.levelsTraced[1][k], 1) + "%",
                       cellNumber(m.viewTraced[k], 1) + "% (" + std::to_string(m.viewSizes[k]) + "²)",
                       cellNumber(m.fillTraced[k], 1) + "%"});
    md += "\nLookups traced (not answered by the cube) in each frame at " + std::to_string(kMultiResolutionFaces) +
          "² faces, one level against multi-resolution cubes, a cube whose resolution follows the view and "
          "a cube also filled from the surfaces the camera sees (docs/caching.md); the goal is at most 5 % "
          "after frame 2:\n\n" +
          traced.toMarkdown();
    out.headlines.push_back("fill-rate " + std::to_string(kMultiResolutionFaces) +
                            "², lookups traced in frame 3: " + cellNumber(m.plainTraced[2], 1) + "% (1 level), " +
                            cellNumber(m.levelsTraced[0][2], 1) + "% (4 levels, bound 0.25), " +
                            cellNumber(m.levelsTraced[1][2], 1) + "% (bound 1), " + cellNumber(m.viewTraced[2], 1) +
                            "% (from the view, " + std::to_string(m.viewSizes[2]) + "² faces), " +
                            cellNumber(m.fillTraced[2], 1) + "% (visible-surface fill); goal ≤ 5%");
    return md;
}

class FillRateExperiment : public Experiment {
public:
    std::string name() const override { return "fill-rate"; }
    std::string title() const override {
        return "Figure 5.9: invalid texels before each frame, camera moving around one caching sphere";
    }
    double estimatedWork(const BenchSettings& settings) const override {
        const double mp = std::pow(fillRateImageSide(settings.size), 2) / 1e6;
        return (5.0 + std::size(kErrorBounds)) * (kSteps + 1) * mp * 1.3;
    }

    ExperimentOutput run(ExperimentContext& context) const override {
        const FillRatePath orbit(context);
        FillRateMeasurements m;
        measureOneLevel(orbit, m);
        measureMultiResolution(orbit, m);
        measureFromViewAndFill(orbit, m);

        const PaperTable documents = paperFigure59();
        writeInvalidTexelsPlot(m, documents, context.dir);
        ExperimentOutput out;
        out.name = name();
        out.title = title();
        out.markdown = fillRateMarkdown(m, documents, orbit.side, out);
        out.plots = {"invalid-texels.svg"};
        writeJsonFile(context.dir / "results.json", resultsJson(m, documents, orbit.side, context));
        writeTextFileAtomically(context.dir / "results.md", experimentMarkdown(out));
        return out;
    }

private:
    nlohmann::json resultsJson(const FillRateMeasurements& m, const PaperTable& documents, int side,
                               const ExperimentContext& context) const {
        return {{"experiment", name()},
                {"title", title()},
                {"size", toString(context.settings.size)},
                {"settings",
                 {{"scene", "behind-0"},
                  {"width", side},
                  {"height", side},
                  {"frames", kSteps + 1},
                  {"degrees_per_frame", kDegreesPerStep},
                  {"resolutions", kFillRateResolutions},
                  {"cache_policy", "always"}}},
                {"environment", toJson(context.environment)},
                {"documents", toJson(documents)},
                {"series", m.series},
                {"multi_resolution", m.multiResolution},
                {"from_view",
                 {{"asked_faces", kMultiResolutionFaces},
                  {"traced_percent", m.viewTraced},
                  {"faces_after_frame", m.viewSizes}}},
                {"visible_fill", {{"faces", kMultiResolutionFaces}, {"traced_percent", m.fillTraced}}}};
    }
};

}  // namespace

std::unique_ptr<Experiment> makeFillRateExperiment() {
    return std::make_unique<FillRateExperiment>();
}

}  // namespace raycache
