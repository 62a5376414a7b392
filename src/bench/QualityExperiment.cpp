#include "bench/QualityExperiment.h"

#include <cmath>

#include "bench/ImageComparison.h"
#include "bench/MarkdownTable.h"
#include "bench/ResultsJson.h"
#include "bench/SvgPlot.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "metrics/Heatmap.h"
#include "render/ImageWriter.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"
#include "trace/TraceScene.h"

namespace raycache {

namespace {

constexpr int kResolutions[] = {128, 256, 512};
// Heat maps on the documents' scale (red = totally different) and stretched
// 4x, where the small differences of a good cache become visible.
constexpr double kStretchedScale = 0.25;
// The second fill protocol: the cube is filled while the camera orbits toward
// the measured view, so texels were stored from other viewpoints (as in use).
constexpr int kOrbitFillFrames = 8;
constexpr float kOrbitDegreesPerFrame = 1.5f;  // the room scene's own orbit speed

// Multi-resolution cubes (docs/caching.md), measured beside the plain cube
// on the orbit fill only, where coarse levels may answer texels the orbit
// left empty at the finest: 4 levels, at the default error bound and at a
// wide one (on room the default lets almost no coarse texel answer).
constexpr int kMultiResolutionLevels = 4;
constexpr float kDefaultErrorBound = 0.25f;
constexpr float kWideErrorBound = 1.0f;

struct Protocol {
    std::string key;
    std::string label;
    std::string shortLabel;  // for plot legends
    bool orbit;              // fill along the orbit, else from the view itself
    int fillFrames;          // frames rendered before the measured one
    int cubeLevels = 1;      // RayCacheSettings::cubeLevels
    float errorBound = kDefaultErrorBound;  // RayCacheSettings::levelErrorBound
    bool viewSized = false;  // RayCacheSettings::resolutionFromView
    VisibleFill fill = VisibleFill::Off;  // RayCacheSettings::visibleFill
};
std::vector<Protocol> fillProtocols() {
    return {{"same", "from the same view", "same-view fill", false, 1},
            {"orbit", "along an orbit (8 frames, 1.5°/frame)", "orbit fill", true, kOrbitFillFrames},
            {"orbit-levels", "along the orbit, 4 resolution levels, error bound 0.25", "orbit fill, 4 levels",
             true, kOrbitFillFrames, kMultiResolutionLevels, kDefaultErrorBound},
            {"orbit-levels-wide", "along the orbit, 4 resolution levels, error bound 1", "orbit fill, 4 levels, bound 1",
             true, kOrbitFillFrames, kMultiResolutionLevels, kWideErrorBound},
            {"orbit-view", "along the orbit, resolution from the view (at most the column's)", "orbit fill, from view",
             true, kOrbitFillFrames, 1, kDefaultErrorBound, true},
            {"orbit-visible-fill", "along the orbit, also filled from visible surfaces (exact)",
             "orbit fill, visible fill", true, kOrbitFillFrames, 1, kDefaultErrorBound, false, VisibleFill::Exact}};
}

int qualityImageSide(BenchSize size) {
    return size == BenchSize::Full ? 1024 : size == BenchSize::Quick ? 512 : 40;
}

struct View {
    std::string key;
    std::string label;
    Camera camera;
};

class QualityExperiment : public Experiment {
public:
    std::string name() const override { return "quality"; }
    std::string title() const override {
        return "Figures 5.1, 5.4, 5.5: CCT image quality vs face resolution, far and close-up (room)";
    }
    double estimatedWork(const BenchSettings& settings) const override {
        const double mp = std::pow(qualityImageSide(settings.size), 2) / 1e6;
        // Per view: the reference, then per resolution the same-view fill (2
        // frames) and every orbit protocol (fill frames + the measured one).
        const double orbitProtocols = static_cast<double>(fillProtocols().size()) - 1.0;
        return 2.0 * (1.0 + 3.0 * (2.0 + orbitProtocols * (kOrbitFillFrames + 1.0))) * mp * 1.5;
    }

    ExperimentOutput run(ExperimentContext& context) const override {
        const int side = qualityImageSide(context.settings.size);
        const double frameWork = static_cast<double>(side) * side / 1e6 * 1.5;
        std::optional<Scene> maybeScene = makeBuiltinScene("room");
        if (!maybeScene) throw RuntimeError("built-in scene room is missing");
        const Scene& scene = *maybeScene;
        const TraceScene tracer(scene);

        // The close-up looks at the mirror ball from 40% of the far camera's distance.
        const Vec3 ball{0.0f, 1.5f, 0.0f};
        Camera close = scene.camera;
        close.lookAt = ball;
        close.position = ball + (scene.camera.position - ball) * 0.4f;
        const std::vector<View> views{{"far", "far", scene.camera}, {"close", "close-up", close}};

        ExperimentOutput out;
        out.name = name();
        out.title = title();
        nlohmann::json rows = nlohmann::json::array();
        MarkdownTable table({"view", "cube filled", "face resolution", "MAE", "PSNR (dB)", "SSIM", "hit rate",
                             "heat map", "heat map ×4"});
        SvgPlot plot;
        plot.title = "quality: PSNR of CCT against the uncached render";
        plot.xLabel = "cube face resolution";
        plot.yLabel = "PSNR (dB)";
        for (int r : kResolutions) plot.categories.push_back(std::to_string(r) + "²");

        for (const View& view : views) {
            context.progress.step("quality: " + view.label + " view");
            RenderSettings plainSettings;
            plainSettings.width = plainSettings.height = side;
            plainSettings.threads = context.settings.threads;
            plainSettings.cache.techniqueOverride = CacheTechnique::None;
            RenderSession plain(scene, plainSettings, tracer, context.parallel);
            Image reference;
            plain.render(view.camera, reference);
            context.progress.advance(frameWork);
            const std::string referenceName = view.key + "-uncached.png";
            writeImage(reference, context.dir / referenceName);
            out.images.push_back(referenceName);

            for (const Protocol& protocol : fillProtocols()) {
                PlotSeries series{view.label + ", " + protocol.shortLabel, {}};
                std::string psnrs, ssims;
                // The orbit the cube is filled along ends at the measured view.
                CameraPath orbit;
                orbit.kind = CameraPathKind::Orbit;
                orbit.center = view.camera.lookAt;
                orbit.degreesPerFrame = kOrbitDegreesPerFrame;
                for (std::size_t ri = 0; ri < std::size(kResolutions); ++ri) {
                    const int resolution = kResolutions[ri];
                    RenderSettings settings = plainSettings;
                    settings.cache.techniqueOverride = CacheTechnique::Cct;
                    settings.cache.resolutionOverride = resolution;
                    settings.cache.cubeLevels = protocol.cubeLevels;
                    settings.cache.levelErrorBound = protocol.errorBound;
                    settings.cache.resolutionFromView = protocol.viewSized;
                    settings.cache.visibleFill = protocol.fill;
                    RenderSession cached(scene, settings, tracer, context.parallel);
                    Image image;
                    for (int f = -protocol.fillFrames; f < 0; ++f) {
                        cached.render(protocol.orbit ? orbit.cameraAt(view.camera, f) : view.camera, image);
                        context.progress.advance(frameWork);
                    }
                    const FrameStats stats = cached.render(view.camera, image);
                    context.progress.advance(frameWork);
                    const ImageComparison c = compareImages(image, reference);
                    const double hit = stats.cache && stats.cache->lookups()
                                           ? 100.0 * static_cast<double>(stats.cache->hits()) /
                                                 static_cast<double>(stats.cache->lookups())
                                           : 0.0;

                    const std::string stem = view.key + "-" + protocol.key + "-cct-" + std::to_string(resolution);
                    writeImage(image, context.dir / (stem + ".png"));
                    writeImage(renderHeatmap(image, reference, {1.0}), context.dir / (stem + "-heatmap.png"));
                    writeImage(renderHeatmap(image, reference, {kStretchedScale}),
                               context.dir / (stem + "-heatmap-x4.png"));
                    out.images.insert(out.images.end(),
                                      {stem + ".png", stem + "-heatmap.png", stem + "-heatmap-x4.png"});
                    table.addRow({view.label, protocol.label, std::to_string(resolution) + "²", cellNumber(c.mae, 5),
                                  std::isinf(c.psnr) ? "∞ (identical)" : cellNumber(c.psnr, 2), cellNumber(c.ssim, 4),
                                  cellNumber(hit, 1) + "%", "![](" + stem + "-heatmap.png)",
                                  "![](" + stem + "-heatmap-x4.png)"});
                    rows.push_back(
                        {{"view", view.key},
                         {"fill", protocol.key},
                         {"fill_frames", protocol.fillFrames},
                         {"cube_levels", protocol.cubeLevels},
                         {"level_error_bound", protocol.errorBound},
                         {"resolution_from_view", protocol.viewSized},
                         {"visible_fill", protocol.fill != VisibleFill::Off},
                         {"camera",
                          {{"position", {view.camera.position.x, view.camera.position.y, view.camera.position.z}},
                           {"look_at", {view.camera.lookAt.x, view.camera.lookAt.y, view.camera.lookAt.z}}}},
                         {"resolution", resolution},
                         {"metrics", toJson(c)},
                         {"hit_percent", hit},
                         {"image", stem + ".png"},
                         {"heatmap", stem + "-heatmap.png"},
                         {"heatmap_x4", stem + "-heatmap-x4.png"}});
                    series.points.push_back({static_cast<double>(ri), c.psnr});
                    psnrs +=
                        (psnrs.empty() ? "" : " / ") + (std::isinf(c.psnr) ? std::string("∞") : cellNumber(c.psnr, 1));
                    ssims += (ssims.empty() ? "" : " / ") + cellNumber(c.ssim, 3);
                }
                out.headlines.push_back("quality " + view.label + ", cube filled " + protocol.label + ": PSNR " +
                                        psnrs + " dB, SSIM " + ssims + " at 128² / 256² / 512²");
                plot.series.push_back(std::move(series));
            }
        }
        writeSvgPlot(plot, (context.dir / "psnr-vs-resolution.svg").string());
        out.plots = {"psnr-vs-resolution.svg"};
        out.markdown =
            "The room scene at " + std::to_string(side) + "x" + std::to_string(side) +
            ", max depth 6; the close-up looks at the mirror ball from 40 % of the far camera's distance. For "
            "each view and face resolution the cube starts empty and is filled in one of two ways, then the view "
            "is rendered from the cube and compared with the uncached render (the ground truth): *from the same "
            "view* (one frame of the view itself: the error is nearest-neighbour texel sharing alone), and *along "
            "an orbit* (the camera orbits toward the view, 8 frames of 1.5°: texels were stored from other "
            "viewpoints, adding CCT's missing parallax); the orbit fill is measured again with multi-resolution "
            "cubes (4 levels, error bound 0.25 and 1: a coarser texel answers where the finest is empty and the "
            "pixel's footprint allows, docs/caching.md), with the cube's resolution chosen from the view (at most "
            "the column's) and with texels also filled from the surfaces the camera sees (exact fill). "
            "Metrics on the displayed (sRGB) images: MAE in [0,1] (the documents' single number), PSNR, SSIM "
            "(11×11 Gaussian window). Heat maps: per-pixel absolute difference, blue = same, red = totally "
            "different (the documents' scale), and the same stretched 4× (red = 0.25).\n\n" +
            table.toMarkdown() +
            "\nThe documents show these differences as pictures only (Figs 5.1, 5.4, 5.5): visible at "
            "silhouettes, checkerboard edges in reflections and in close-ups (nearest-neighbour pixelation).\n";
        writeJsonFile(context.dir / "results.json", {{"experiment", name()},
                                                     {"title", title()},
                                                     {"size", toString(context.settings.size)},
                                                     {"settings",
                                                      {{"scene", "room"},
                                                       {"width", side},
                                                       {"height", side},
                                                       {"resolutions", kResolutions},
                                                       {"orbit_fill_frames", kOrbitFillFrames},
                                                       {"orbit_degrees_per_frame", kOrbitDegreesPerFrame},
                                                       {"multi_resolution_levels", kMultiResolutionLevels},
                                                       {"cache_policy", "always"}}},
                                                     {"environment", toJson(context.environment)},
                                                     {"rows", rows}});
        writeTextFileAtomically(context.dir / "results.md", experimentMarkdown(out));
        return out;
    }
};

}  // namespace

std::unique_ptr<Experiment> makeQualityExperiment() {
    return std::make_unique<QualityExperiment>();
}

}  // namespace raycache
