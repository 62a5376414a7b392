#include "bench/ParallaxExperiment.h"

#include <chrono>
#include <cmath>

#include "bench/ImageComparison.h"
#include "bench/MarkdownTable.h"
#include "bench/ResultsJson.h"
#include "bench/SvgPlot.h"
#include "core/AtomicFile.h"
#include "core/Errors.h"
#include "core/SampleSummary.h"
#include "metrics/Heatmap.h"
#include "render/ImageWriter.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"
#include "trace/TraceScene.h"

namespace raycache {

namespace {

struct CachedVariant {
    std::string key;
    std::string label;
    CacheTechnique technique;
};

// CCT, the thesis' CDCT and the improved CDCT.
std::vector<CachedVariant> parallaxVariants() {
    return {{"cct", "CCT", CacheTechnique::Cct},
            {"cdct-parity", "CDCT parity 0.4/0.05", CacheTechnique::CdctParity},
            {"cdct", "improved CDCT", CacheTechnique::Cdct}};
}

int parallaxImageSide(BenchSize size) {
    return size == BenchSize::Full ? 1024 : size == BenchSize::Quick ? 512 : 32;
}
int parallaxFrameCount(BenchSize size) {
    return size == BenchSize::Tiny ? 3 : 25;
}

class ParallaxExperiment : public Experiment {
public:
    std::string name() const override { return "parallax"; }
    std::string title() const override {
        return "Figure 3.5: parallax, CCT vs CDCT vs uncached along a camera move (parallax scene)";
    }
    double estimatedWork(const BenchSettings& settings) const override {
        const double mp = std::pow(parallaxImageSide(settings.size), 2) / 1e6;
        return parallaxFrameCount(settings.size) * mp * (1.0 + 1.5 * static_cast<double>(parallaxVariants().size()));
    }

    bool honoursCachePolicy() const override { return true; }

    ExperimentOutput run(ExperimentContext& context) const override {
        const int side = parallaxImageSide(context.settings.size);
        const int frames = parallaxFrameCount(context.settings.size);
        const double mp = static_cast<double>(side) * side / 1e6;
        std::optional<Scene> maybeScene = makeBuiltinScene("parallax");
        if (!maybeScene) throw RuntimeError("built-in scene parallax is missing");
        const Scene& scene = *maybeScene;
        const TraceScene tracer(scene);
        const std::vector<CachedVariant> variants = parallaxVariants();

        RenderSettings plainSettings;
        plainSettings.width = plainSettings.height = side;
        plainSettings.threads = context.settings.threads;
        plainSettings.cache.techniqueOverride = CacheTechnique::None;
        RenderSession plain(scene, plainSettings, tracer, context.parallel);
        std::vector<std::unique_ptr<RenderSession>> renderers;
        for (const CachedVariant& v : variants) {
            RenderSettings s = plainSettings;
            s.cache.techniqueOverride = v.technique;
            s.cache.policy = context.settings.cachePolicy;
            s.cache.cdctStepOverride = 0.4f;  // the thesis' middle pair, depths up to 100
            s.cache.cdctEpsilonOverride = 0.05f;
            s.cache.cdctMaxDepthOverride = 100.0f;
            renderers.push_back(std::make_unique<RenderSession>(scene, s, tracer, context.parallel));
        }

        context.progress.step("parallax: " + std::to_string(frames) + " frames");
        const auto timed = [](const auto& render) {
            const auto start = std::chrono::steady_clock::now();
            FrameStats stats = render();
            return std::pair{
                stats, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count()};
        };
        std::vector<double> referenceMs;
        std::vector<std::vector<double>> ms(variants.size()), hit(variants.size());
        std::vector<std::vector<ImageComparison>> metrics(variants.size());
        Image reference;
        std::vector<Image> images(variants.size());
        for (int f = 0; f < frames; ++f) {
            const Camera camera = scene.cameraPath.cameraAt(scene.camera, f);
            referenceMs.push_back(timed([&] { return plain.render(camera, reference); }).second);
            context.progress.advance(mp);
            for (std::size_t vi = 0; vi < variants.size(); ++vi) {
                const auto [stats, t] = timed([&] { return renderers[vi]->render(camera, images[vi]); });
                ms[vi].push_back(t);
                hit[vi].push_back(stats.cache && stats.cache->lookups()
                                      ? 100.0 * static_cast<double>(stats.cache->hits()) /
                                            static_cast<double>(stats.cache->lookups())
                                      : 0.0);
                metrics[vi].push_back(compareImages(images[vi], reference));
                context.progress.advance(1.5 * mp);
            }
        }

        // The last frame's images and heat maps.
        ExperimentOutput out;
        out.name = name();
        out.title = title();
        writeImage(reference, context.dir / "last-uncached.png");
        out.images.push_back("last-uncached.png");
        for (std::size_t vi = 0; vi < variants.size(); ++vi) {
            const std::string stem = "last-" + variants[vi].key;
            writeImage(images[vi], context.dir / (stem + ".png"));
            writeImage(renderHeatmap(images[vi], reference, {1.0}), context.dir / (stem + "-heatmap.png"));
            writeImage(renderHeatmap(images[vi], reference, {0.25}), context.dir / (stem + "-heatmap-x4.png"));
            out.images.insert(out.images.end(), {stem + ".png", stem + "-heatmap.png", stem + "-heatmap-x4.png"});
        }

        SvgPlot maePlot, psnrPlot;
        maePlot.title = "parallax: error per frame against the uncached render";
        maePlot.xLabel = "frame";
        maePlot.yLabel = "MAE (displayed, 0..1)";
        psnrPlot.title = "parallax: PSNR per frame against the uncached render";
        psnrPlot.xLabel = "frame";
        psnrPlot.yLabel = "PSNR (dB)";
        nlohmann::json variantsJson = nlohmann::json::array();
        MarkdownTable table({"variant", "MAE median (min–max)", "PSNR dB median (min–max)", "SSIM median (min–max)",
                             "hit rate, last frame", "ms per frame median (min–max)"});
        table.addRow({"uncached (reference)", "0", "∞", "1", "–", cellRange(summarize(referenceMs), 1)});
        for (std::size_t vi = 0; vi < variants.size(); ++vi) {
            std::vector<double> mae, peak, structural;
            nlohmann::json perFrame = nlohmann::json::array();
            PlotSeries maeSeries{variants[vi].label, {}}, psnrSeries{variants[vi].label, {}};
            for (int f = 0; f < frames; ++f) {
                const ImageComparison& c = metrics[vi][static_cast<std::size_t>(f)];
                mae.push_back(c.mae);
                if (std::isfinite(c.psnr)) peak.push_back(c.psnr);
                structural.push_back(c.ssim);
                nlohmann::json frame = toJson(c);
                frame["frame"] = f;
                frame["ms"] = ms[vi][static_cast<std::size_t>(f)];
                frame["hit_percent"] = hit[vi][static_cast<std::size_t>(f)];
                perFrame.push_back(std::move(frame));
                maeSeries.points.push_back({static_cast<double>(f), c.mae});
                psnrSeries.points.push_back({static_cast<double>(f), c.psnr});
            }
            // PSNR is infinite for frames identical to the reference; the range covers the others.
            const std::string psnrCell = peak.empty() ? "∞ (every frame identical)"
                                                      : cellRange(summarize(peak), 2) +
                                                            (peak.size() < mae.size() ? ", some frames identical" : "");
            table.addRow({variants[vi].label, cellRange(summarize(mae), 5), psnrCell,
                          cellRange(summarize(structural), 4), cellNumber(hit[vi].back(), 1) + "%",
                          cellRange(summarize(ms[vi]), 1)});
            out.headlines.push_back("parallax " + variants[vi].label + ": median MAE " +
                                    cellNumber(summarize(mae).median, 5) + ", median PSNR " +
                                    (peak.empty() ? std::string("∞") : cellNumber(summarize(peak).median, 2) + " dB") +
                                    " over " + std::to_string(frames) + " frames, cache hit rate " +
                                    cellNumber(hit[vi].back(), 1) + "% in the last frame");
            variantsJson.push_back({{"key", variants[vi].key}, {"label", variants[vi].label}, {"frames", perFrame}});
            maePlot.series.push_back(std::move(maeSeries));
            psnrPlot.series.push_back(std::move(psnrSeries));
        }
        writeSvgPlot(maePlot, (context.dir / "error-per-frame.svg").string());
        writeSvgPlot(psnrPlot, (context.dir / "psnr-per-frame.svg").string());
        out.plots = {"error-per-frame.svg", "psnr-per-frame.svg"};
        out.markdown =
            "The parallax scene at " + std::to_string(side) + "x" + std::to_string(side) +
            ": two facing mirror "
            "spheres, a near box and a far checkered wall; the camera slides sideways over " +
            std::to_string(frames) +
            " frames. Caches start empty and fill as the camera moves; every frame is "
            "rendered uncached (the reference), then with each cached variant, and compared. CCT looks cached "
            "colors up by direction only, so near objects seen in a mirror appear where they were when cached; "
            "CDCT searches the cached depths along the ray.\n\n" +
            table.toMarkdown() + "\nThe documents show parallax in pictures (Fig 3.5) without numbers.\n";
        writeJsonFile(context.dir / "results.json",
                      {{"experiment", name()},
                       {"title", title()},
                       {"size", toString(context.settings.size)},
                       {"settings",
                        {{"scene", "parallax"},
                         {"width", side},
                         {"height", side},
                         {"frames", frames},
                         {"cdct", {{"step", 0.4}, {"epsilon", 0.05}, {"max_depth", 100}}},
                         {"cache_policy", cachePolicyModeName(context.settings.cachePolicy)}}},
                       {"environment", toJson(context.environment)},
                       {"reference_ms", referenceMs},
                       {"variants", variantsJson}});
        writeTextFileAtomically(context.dir / "results.md", experimentMarkdown(out));
        return out;
    }
};

}  // namespace

std::unique_ptr<Experiment> makeParallaxExperiment() {
    return std::make_unique<ParallaxExperiment>();
}

}  // namespace raycache
