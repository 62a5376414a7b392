// The viewer's render thread renders what the offline renderer renders:
// the same path frames with the same caches give the same 8-bit codes.
#include "viewer/RenderWorker.h"

#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <thread>

#include "core/ColorSpace.h"
#include "scene/BuiltinScenes.h"
#include "session/FrameLoop.h"
#include "session/RenderSession.h"
#include "viewer/CacheLevelOverlayImage.h"
#include "viewer/PipelineChoice.h"
#include "viewer/RenderCacheOverlayImage.h"
#include "viewer/TechniqueChoice.h"

using namespace raycache;

namespace {

std::vector<std::uint8_t> srgb8(const Image& film) {
    std::vector<std::uint8_t> out;
    for (const Rgb& p : film.pixels()) {
        out.push_back(linearToSrgb8(p.r));
        out.push_back(linearToSrgb8(p.g));
        out.push_back(linearToSrgb8(p.b));
        out.push_back(255);
    }
    return out;
}

RenderSettings smallSettings() {
    RenderSettings s;
    s.width = 96;
    s.height = 64;
    s.threads = 2;
    s.cache.resolutionOverride = 64;
    return s;
}

// The frames the offline renderer makes along the scene's path, as 8-bit sRGB.
std::vector<std::vector<std::uint8_t>> offlineFrames(const Scene& scene, const RenderSettings& settings, int frames,
                                                     const std::optional<FrameTimeline>& timeline = std::nullopt) {
    std::vector<std::vector<std::uint8_t>> out;
    renderFrames(
        scene, scene.cameraPath, settings, frames,
        [&](const FrameResult&, const Image& film, const RayCache&) { out.push_back(srgb8(film)); }, {}, timeline);
    return out;
}

// Takes frames until `done` says stop (or a generous timeout).
template <typename Done>
void takeFrames(FrameHandoff& handoff, RenderWorker& worker, Done&& done) {
    DisplayFrame frame;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
        if (auto error = worker.error()) std::rethrow_exception(error);
        if (handoff.take(frame)) {
            if (done(frame)) return;
        } else {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    }
    FAIL() << "no frame in time";
}

// A request for `camera` at `settings`' size, without caching, through
// pipeline choice `pipeline` (viewer/PipelineChoice.h).
RenderRequest uncachedRequest(const Camera& camera, const RenderSettings& settings, int pipeline) {
    RenderRequest request;
    request.camera = camera;
    request.width = settings.width;
    request.height = settings.height;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::None);
    request.config.pipeline = pipeline;
    return request;
}

}  // namespace

TEST(RenderWorker, ScriptedRunShowsEveryPathFrameAsTheOfflineRendererDoes) {
    const Scene scene = *makeBuiltinScene("room");  // a mirror ball that caches (CCT)
    const TraceScene tracer(scene);
    RenderSettings settings = smallSettings();
    settings.cache.techniqueOverride = CacheTechnique::Cct;
    constexpr int kFrames = 5;

    const std::vector<std::vector<std::uint8_t>> offline = offlineFrames(scene, settings, kFrames);

    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), kFrames, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request;
    request.width = settings.width;
    request.height = settings.height;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::Cct);
    request.inspectObject = 1;  // the mirror ball
    request.inspectorFaceSize = 16;
    worker.submit(request);
    int next = 0;
    double lastInvalid = 101.0;
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_EQ(f.pathFrame, next);
        EXPECT_EQ(f.rgba, offline[static_cast<std::size_t>(next)]) << "frame " << next;
        EXPECT_TRUE(f.stats.cache.has_value());
        EXPECT_EQ(f.inspectedObject, 1);
        EXPECT_EQ(f.inspectorWidth, 64);
        EXPECT_LT(f.inspectedInvalidPercent, lastInvalid);  // the cube fills
        lastInvalid = f.inspectedInvalidPercent;
        ++next;
        return next == kFrames;
    });
    EXPECT_EQ(next, kFrames);
    // Wait for the worker to stop on its own.
    for (int i = 0; i < 1000 && !worker.finished(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_TRUE(worker.finished());
    EXPECT_FALSE(worker.error());
}

TEST(RenderWorker, ScriptedRunOfAnAnimatedSceneShowsEachFramesMomentAsTheOfflineRendererDoes) {
    const Scene scene = *makeBuiltinScene("orbit");  // four spheres circling, two of them caching mirrors
    const TraceScene tracer(scene);
    RenderSettings settings = smallSettings();
    settings.cache.techniqueOverride = CacheTechnique::Cct;
    constexpr int kFrames = 3;
    const FrameTimeline timeline{0.5f, 10.0f};

    const std::vector<std::vector<std::uint8_t>> offline = offlineFrames(scene, settings, kFrames, timeline);

    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, timeline, smallSettings(), kFrames, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request;
    request.width = settings.width;
    request.height = settings.height;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::Cct);
    request.time = 7.0f;  // ignored by a scripted run: the path frame sets the moment
    worker.submit(request);
    int next = 0;
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_EQ(f.pathFrame, next);
        EXPECT_EQ(f.rgba, offline[static_cast<std::size_t>(next)]) << "frame " << next;
        EXPECT_TRUE(f.stats.sceneUpdate.has_value());
        ++next;
        return next == kFrames;
    });
    EXPECT_EQ(next, kFrames);
    for (int i = 0; i < 1000 && !worker.finished(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_FALSE(worker.error());
}

TEST(RenderWorker, DifferenceToTheUncachedImageIsZeroWithoutCaching) {
    const Scene scene = *makeBuiltinScene("room");
    const TraceScene tracer(scene);
    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), std::nullopt, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request;
    request.camera = scene.camera;
    request.width = 48;
    request.height = 32;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::None);
    request.difference = true;
    worker.submit(request);
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_TRUE(f.showsDifference);
        EXPECT_EQ(f.width, 48);
        EXPECT_EQ(f.meanDifference, 0.0);
        std::size_t notBlue = 0;
        for (std::size_t i = 0; i < f.rgba.size(); i += 4) notBlue += f.rgba[i] != 0 || f.rgba[i + 2] != 255;
        EXPECT_EQ(notBlue, 0u);
        return true;
    });
}

TEST(RenderWorker, RejectedSettingsKeepTheLastGoodOnesAndSayWhy) {
    const Scene scene = *makeBuiltinScene("room");
    const TraceScene tracer(scene);
    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), std::nullopt, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request;
    request.camera = scene.camera;
    request.width = 32;
    request.height = 32;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::Cct);
    request.continuous = false;
    worker.submit(request);
    takeFrames(handoff, worker, [&](const DisplayFrame& f) { return f.configError.empty() && f.stats.cache; });
    request.config.technique = techniqueChoiceIndex(CacheTechnique::Cdct);
    request.config.cdctStep = 0.1f;
    request.config.cdctEpsilon = 0.2f;  // not below the step
    worker.submit(request);
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_NE(f.configError.find("epsilon"), std::string::npos);
        EXPECT_TRUE(f.stats.cache.has_value());  // still rendering, with CCT
        return true;
    });
}

TEST(RenderWorker, RenderCacheFramesAreTheOfflineRenderCachesFrames) {
    const Scene scene = *makeBuiltinScene("room");
    const TraceScene tracer(scene);
    RenderSettings settings = smallSettings();
    settings.cache.techniqueOverride = CacheTechnique::Cct;
    settings.pipeline = PipelineKind::RenderCache;
    constexpr int kFrames = 4;

    const std::vector<std::vector<std::uint8_t>> offline = offlineFrames(scene, settings, kFrames);

    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), kFrames, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request;
    request.width = settings.width;
    request.height = settings.height;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::Cct);
    request.config.pipeline = kRenderCacheChoice;
    worker.submit(request);
    int next = 0;
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_EQ(f.pathFrame, next);
        EXPECT_EQ(f.rgba, offline[static_cast<std::size_t>(next)]) << "frame " << next;
        EXPECT_TRUE(f.stats.renderCache.has_value());
        if (f.stats.renderCache) {
            EXPECT_EQ(f.stats.renderCache->refreshedAll, next == 0);
        }
        ++next;
        return next == kFrames;
    });
    EXPECT_EQ(next, kFrames);
    for (int i = 0; i < 1000 && !worker.finished(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_FALSE(worker.error());
}

// The heat map compares the rendered image with the uncached one, never an
// overlay's tints: with the difference view on, the Render Cache's overlay
// changes nothing.
TEST(RenderWorker, DifferenceViewIgnoresTheRenderCacheOverlay) {
    const Scene scene = *makeBuiltinScene("room");
    const TraceScene tracer(scene);
    const auto firstFrame = [&](RenderCacheOverlay overlay) {
        FrameHandoff handoff;
        // Scripted, one frame: every frame is handed over, so the frame taken
        // is always the first (an interactive worker keeps rendering, and a
        // later Render Cache frame may replace the first before it is taken).
        RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), 1, {}};
        RenderWorker worker(setup, handoff);
        RenderRequest request;
        request.width = 48;
        request.height = 32;
        request.config.technique = techniqueChoiceIndex(CacheTechnique::Cct);
        request.config.pipeline = kRenderCacheChoice;
        request.renderCacheOverlay = static_cast<int>(overlay);
        request.difference = true;
        worker.submit(request);
        std::vector<std::uint8_t> rgba;
        takeFrames(handoff, worker, [&](const DisplayFrame& f) {
            EXPECT_TRUE(f.showsDifference);
            rgba = f.rgba;
            return true;
        });
        return rgba;
    };
    const std::vector<std::uint8_t> plain = firstFrame(RenderCacheOverlay::None);
    ASSERT_FALSE(plain.empty());
    EXPECT_EQ(firstFrame(RenderCacheOverlay::Sources), plain);
    EXPECT_EQ(firstFrame(RenderCacheOverlay::Requests), plain);
}

TEST(RenderWorker, CubeLevelOverlayIsTheOfflineRecordPaintedOverTheOfflineFrame) {
    const Scene scene = *makeBuiltinScene("room");
    const TraceScene tracer(scene);
    RenderSettings settings = smallSettings();
    settings.cache.techniqueOverride = CacheTechnique::Cct;
    settings.recordCacheLevels = true;
    constexpr int kFrames = 3;

    // The offline frames with their records, painted as the viewer paints them.
    std::vector<std::vector<std::uint8_t>> painted;
    std::vector<CacheLevelImage::Counts> counts;
    RenderSession session(scene, settings);
    Image film;
    for (int f = 0; f < kFrames; ++f) {
        session.render(scene.cameraPath.cameraAt(scene.camera, f), film);
        ASSERT_NE(session.cacheLevels(), nullptr);
        painted.push_back(srgb8(film));
        paintCacheLevelOverlay(*session.cacheLevels(), painted.back());
        counts.push_back(session.cacheLevels()->counts());
    }
    EXPECT_GT(counts.back()[2], 0);  // the mirror ball answers from its cube by the last frame
    EXPECT_NE(painted.back(), srgb8(film));

    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), kFrames, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request;
    request.width = settings.width;
    request.height = settings.height;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::Cct);
    request.cacheLevels = true;
    worker.submit(request);
    int next = 0;
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_EQ(f.pathFrame, next);
        EXPECT_TRUE(f.showsCacheLevels);
        EXPECT_EQ(f.rgba, painted[static_cast<std::size_t>(next)]) << "frame " << next;
        EXPECT_EQ(f.cacheLevelPixels, counts[static_cast<std::size_t>(next)]) << "frame " << next;
        ++next;
        return next == kFrames;
    });
    EXPECT_EQ(next, kFrames);
    for (int i = 0; i < 1000 && !worker.finished(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    EXPECT_FALSE(worker.error());
}

TEST(RenderCacheOverlay, SourcesTintEachStateAndRequestsMarkTheRequestedPixels) {
    RenderCacheOverlays o;
    o.width = 4;
    o.height = 2;
    o.state = {PixelState::Reprojected, PixelState::Fresh,     PixelState::Culled,   PixelState::Filled3x3,
               PixelState::Filled7x7,   PixelState::Unfilled, PixelState::Hole,     PixelState::Reprojected};
    const std::vector<std::uint8_t> grey(4 * 8, 100);
    std::vector<std::uint8_t> rgba = grey;
    paintRenderCacheOverlay(o, RenderCacheOverlay::Sources, rgba);
    const auto pixel = [&](int i) { return std::vector<int>{rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]}; };
    EXPECT_EQ(pixel(0), (std::vector<int>{100, 100, 100}));  // reprojected: as it is
    // blend(c, target, a) = (c (256 - a) + target a) / 256
    EXPECT_EQ(pixel(1), (std::vector<int>{(100 * 96) >> 8, (100 * 96 + 255 * 160) >> 8, (100 * 96) >> 8}));
    EXPECT_EQ(pixel(2), (std::vector<int>{(100 * 56 + 255 * 200) >> 8, (100 * 56) >> 8, (100 * 56 + 255 * 200) >> 8}));
    EXPECT_EQ(pixel(3), (std::vector<int>{(100 * 56 + 255 * 200) >> 8, (100 * 56 + 255 * 200) >> 8, (100 * 56) >> 8}));
    EXPECT_EQ(pixel(5), (std::vector<int>{255, 0, 0}));  // unfilled: pure red
    EXPECT_EQ(pixel(7), (std::vector<int>{100, 100, 100}));

    rgba = grey;
    o.requests.tileSize = 2;
    o.requests.tilesX = 2;
    o.requests.tilesY = 1;
    o.requests.tilePriority = {0.0f, 4.0f};
    o.requests.pixels = {{1, 1}};
    paintRenderCacheOverlay(o, RenderCacheOverlay::Requests, rgba);
    EXPECT_EQ(pixel(0), (std::vector<int>{100, 100, 100}));             // priority 0: untinted
    EXPECT_EQ(pixel(5), (std::vector<int>{255, 255, 255}));             // requested (1, 1): white
    EXPECT_EQ(pixel(2), (std::vector<int>{(100 * 56) >> 8, (100 * 56 + 64 * 200) >> 8, (100 * 56 + 255 * 200) >> 8}));

    rgba.resize(4);  // the frame after a resize: sizes differ, nothing painted
    paintRenderCacheOverlay(o, RenderCacheOverlay::Sources, rgba);
    EXPECT_EQ(rgba, std::vector<std::uint8_t>(4, 100));
}

// The Render Cache at its own rate (RenderCacheDisplay::Async): with the
// camera held still the frames shown converge to the full render's codes,
// the frame says so and gives the tracer's rates, and the worker stops
// (joining the tracer, which never runs out of requests) when destroyed.
TEST(RenderWorker, AsyncRenderCacheWithAStillCameraConvergesToTheFullRender) {
    const Scene scene = *makeBuiltinScene("room");
    const TraceScene tracer(scene);
    RenderSettings settings = smallSettings();
    settings.cache.techniqueOverride = CacheTechnique::None;
    Image reference;
    RenderSession(scene, settings).render(scene.camera, reference);  // the ray pipeline
    const std::vector<std::uint8_t> expected = srgb8(reference);

    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), std::nullopt, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request = uncachedRequest(scene.camera, settings, kRenderCacheChoice);
    request.renderCacheAsync = true;
    worker.submit(request);
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_TRUE(f.asyncRenderCache);
        EXPECT_EQ(f.displayThreads, 2);
        EXPECT_EQ(f.traceThreads, 1);
        EXPECT_TRUE(f.stats.renderCache.has_value());
        if (f.stats.renderCache) {
            EXPECT_EQ(f.stats.renderCache->fresh, 0) << "the display traces no camera ray";
        }
        // The first display frame only issues the first request: it has no
        // samples yet. (The hand-over keeps only the newest frame, so the
        // test may never see it: it checks it when it does.)
        if (f.serial == 1) {
            EXPECT_EQ(f.mergedSamples, 0);
            EXPECT_NE(f.rgba, expected) << "the first display frame has no samples yet";
        }
        return f.rgba == expected;
    });
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_EQ(f.rgba, expected) << "the camera is still: every sample is exact";
        return f.samplesPerSecond > 0.0 && f.displayFps > 0.0;
    });
}

// Pipeline auto: full frames are the ray pipeline's, bit for bit; asked for
// the Render Cache (at its own rate), the worker shows full frames until the
// Render Cache's samples of the whole image have come, then the Render
// Cache, which with the camera still shows the full render's codes again.
TEST(RenderWorker, AutoPipelineShowsFullFramesAndTheRenderCacheWhenAsked) {
    const Scene scene = *makeBuiltinScene("room");
    const TraceScene tracer(scene);
    RenderSettings settings = smallSettings();
    settings.cache.techniqueOverride = CacheTechnique::None;
    Image reference;
    RenderSession(scene, settings).render(scene.camera, reference);  // the ray pipeline
    const std::vector<std::uint8_t> expected = srgb8(reference);

    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), std::nullopt, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request;
    request.camera = scene.camera;
    request.width = settings.width;
    request.height = settings.height;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::None);
    request.config.pipeline = kAutoPipelineChoice;
    request.renderCacheAsync = true;
    worker.submit(request);
    int fullFrames = 0;
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_TRUE(f.autoPipeline);
        EXPECT_EQ(f.shown, ShownPipeline::FullFrame);
        EXPECT_FALSE(f.stats.renderCache.has_value());
        EXPECT_EQ(f.rgba, expected) << "a full frame is the ray pipeline's";
        return ++fullFrames == 3;
    });

    request.showRenderCache = true;
    worker.submit(request);
    // (The hand-over keeps only the newest frame: the test may not see the
    // frames shown while the samples come; it checks them when it does.)
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        if (f.renderCachePriming) {
            EXPECT_EQ(f.shown, ShownPipeline::FullFrame);
            EXPECT_EQ(f.rgba, expected) << "while its samples come, the full frame";
        }
        return f.shown == ShownPipeline::RenderCache && f.rgba == expected;
    });

    // Back to full frames (the camera stopped): the ray pipeline's again.
    request.showRenderCache = false;
    worker.submit(request);
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        if (f.shown != ShownPipeline::FullFrame) return false;
        EXPECT_EQ(f.rgba, expected);
        return true;
    });
}

// Pipeline auto with the synchronous Render Cache: its frames are the
// offline Render Cache's along the same cameras.
TEST(RenderWorker, AutoPipelineSyncRenderCacheFramesAreTheOfflineRenderCachesFrames) {
    const Scene scene = *makeBuiltinScene("room");
    const TraceScene tracer(scene);
    RenderSettings settings = smallSettings();
    settings.cache.techniqueOverride = CacheTechnique::None;
    settings.pipeline = PipelineKind::RenderCache;
    RenderSession offline(scene, settings);
    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), std::nullopt, {}};
    RenderWorker worker(setup, handoff);
    RenderRequest request;
    request.width = settings.width;
    request.height = settings.height;
    request.config.technique = techniqueChoiceIndex(CacheTechnique::None);
    request.config.pipeline = kAutoPipelineChoice;
    request.showRenderCache = true;
    request.continuous = false;
    for (int i = 0; i < 3; ++i) {
        request.camera = scene.cameraPath.cameraAt(scene.camera, i);
        Image film;
        offline.render(request.camera, film);
        worker.submit(request);
        takeFrames(handoff, worker, [&](const DisplayFrame& f) {
            if (!(f.camera == request.camera)) return false;
            EXPECT_EQ(f.shown, ShownPipeline::RenderCache);
            EXPECT_TRUE(f.stats.renderCache.has_value());
            EXPECT_EQ(f.rgba, srgb8(film)) << "frame " << i;
            return true;
        });
    }
}

// --spp N in the viewer: a still view shows the plain frame first, then one
// more sample layer a frame, and after N layers exactly the image `raycache
// render --spp N` makes of the same view. A new view starts again from the
// plain frame.
TEST(RenderWorker, AStillViewIsRefinedToTheOfflineSampledImage) {
    const Scene scene = *makeBuiltinScene("glass");  // edges, a checker and refraction: jitter shows
    const TraceScene tracer(scene);
    constexpr int kSamples = 4;
    RenderSettings settings = smallSettings();
    settings.cache.techniqueOverride = CacheTechnique::None;
    const Parallel parallel(2);
    RenderSession plain(scene, settings, tracer, parallel);
    Image plainFilm;
    plain.render(scene.camera, plainFilm);
    settings.samplesPerPixel = kSamples;
    RenderSession sampled(scene, settings, tracer, parallel);
    Image sampledFilm;
    sampled.render(scene.camera, sampledFilm);
    ASSERT_NE(srgb8(plainFilm), srgb8(sampledFilm));  // else the test could not tell them apart

    FrameHandoff handoff;
    RenderWorkerSetup setup{&scene, &tracer, scene.cameraPath, {}, smallSettings(), std::nullopt, {}};
    setup.samplesPerPixel = kSamples;
    RenderWorker worker(setup, handoff);
    RenderRequest request = uncachedRequest(scene.camera, settings, kAutoPipelineChoice);
    worker.submit(request);
    // The handoff keeps only the newest frame, so a frame may be skipped:
    // the layers never go back, and the first and last are compared.
    int previous = -1;
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        EXPECT_EQ(f.refinementTarget, kSamples);
        EXPECT_GT(f.refinedSamples, previous);
        previous = f.refinedSamples;
        if (f.refinedSamples == 0) {
            EXPECT_EQ(f.rgba, srgb8(plainFilm));
        }
        if (f.refinedSamples == kSamples) {
            EXPECT_EQ(f.rgba, srgb8(sampledFilm));
        }
        return f.refinedSamples >= kSamples || ::testing::Test::HasFailure();
    });
    EXPECT_EQ(previous, kSamples);

    // A new view (the camera moved) starts again: its complete refinement
    // is the offline sampled image of the new camera, not a mix of the two.
    request.camera.position = request.camera.position + Vec3(0.05f, 0.0f, 0.0f);
    sampled.render(request.camera, sampledFilm);
    worker.submit(request);
    takeFrames(handoff, worker, [&](const DisplayFrame& f) {
        if (!(f.camera == request.camera) || f.refinedSamples < kSamples) return false;
        EXPECT_EQ(f.rgba, srgb8(sampledFilm));
        return true;
    });
}
