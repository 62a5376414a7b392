#include "viewer/Viewer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <vector>

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "core/ColorSpace.h"
#include "core/SampleSummary.h"
#include "render/CameraRays.h"
#include "render/ImageWriter.h"
#include "session/FrameReport.h"
#include "trace/TraceScene.h"
#include "viewer/AutoPipelineRule.h"
#include "viewer/FrameHandoff.h"
#include "viewer/FrameTimeHistory.h"
#include "viewer/GlTexture.h"
#include "viewer/PipelineChoice.h"
#include "viewer/RenderWorker.h"
#include "viewer/ViewerCamera.h"
#include "viewer/ViewerPanel.h"
#include "viewer/ViewerWindow.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// How long the camera counts as moving after the last input that moved it.
constexpr double kMovingHoldSeconds = 0.15;

// Writes the back buffer (what the next swap shows) as an image file.
void writeScreenshot(int width, int height, const std::filesystem::path& path) {
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    readBackBuffer(width, height, rgba);
    // Back to linear so the usual writer (atomic, PNG or EXR) takes it; the
    // 8-bit codes survive the round trip exactly (tested).
    std::array<float, 256> linear{};
    for (int i = 0; i < 256; ++i) linear[static_cast<std::size_t>(i)] = srgbToLinear(static_cast<float>(i) / 255.0f);
    Image image(width, height);
    for (std::size_t i = 0; i < image.pixels().size(); ++i)
        image.pixels()[i] = Rgb{linear[rgba[4 * i]], linear[rgba[4 * i + 1]], linear[rgba[4 * i + 2]]};
    writeImage(image, path);
}

std::filesystem::path nextScreenshotPath(const std::string& sceneName, int& counter) {
    for (;;) {
        char name[64];
        std::snprintf(name, sizeof name, "-%04d.png", counter++);
        std::filesystem::path p = "raycache-" + sceneName + name;
        if (!std::filesystem::exists(p)) return p;
    }
}

std::vector<int> cachedObjectsUnder(const Scene& scene, const RenderSettings& base, const ViewerRenderConfig& config) {
    std::vector<int> ids;
    if (!viewerRenderConfigError(scene, base, config).empty()) return ids;
    const RayCacheSettings cache = applyViewerRenderConfig(base, config).cache;
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        if (RayCache::techniqueFor(scene.objects[i], cache) != CacheTechnique::None) ids.push_back(static_cast<int>(i));
    return ids;
}

// One shown frame of a scripted run, for the report.
struct ScriptedSample {
    double intervalMs, renderMs, encodeMs, uploadMs, uiMs, presentMs;
    double samplesPerSecond;  // the async Render Cache's tracer; < 0 otherwise
};

void printScriptedSummary(const std::vector<ScriptedSample>& samples, int warmup, std::ostream& out) {
    std::vector<double> interval, render, encode, upload, ui, present, fps, samplesPerSecond;
    for (std::size_t i = static_cast<std::size_t>(warmup); i < samples.size(); ++i) {
        const ScriptedSample& s = samples[i];
        // The first shown frame has no predecessor: no interval.
        if (i > 0) {
            interval.push_back(s.intervalMs);
            fps.push_back(1000.0 / s.intervalMs);
        }
        render.push_back(s.renderMs);
        encode.push_back(s.encodeMs);
        upload.push_back(s.uploadMs);
        ui.push_back(s.uiMs);
        present.push_back(s.presentMs);
        if (s.samplesPerSecond >= 0.0) samplesPerSecond.push_back(s.samplesPerSecond / 1.0e6);
    }
    const auto line = [&](const char* what, const std::vector<double>& v, int decimals) {
        if (v.empty()) return;
        const SampleSummary s = summarize(v);
        out << "  " << what << " median " << formatFixed(s.median, decimals) << " (min " << formatFixed(s.min, decimals)
            << ", max " << formatFixed(s.max, decimals) << ")\n";
    };
    out << "summary over " << samples.size() - std::min(samples.size(), static_cast<std::size_t>(warmup))
        << " frames after " << warmup << " warm-up frames:\n";
    line("fps              ", fps, 1);
    line("frame interval ms", interval, 1);
    line("render ms        ", render, 1);
    line("encode ms        ", encode, 2);
    line("upload ms        ", upload, 2);
    line("ui ms            ", ui, 2);
    line("present ms       ", present, 2);
    line("trace Msamples/s ", samplesPerSecond, 3);
}

// Mouse and keys while the panel does not take them: the camera, a click
// that picks the object to inspect, and the keys' one-off actions. Returns
// whether the camera moved.
bool applyInput(ViewerWindow& window, ViewerCamera& camera, float dt, const std::vector<int>& keyPresses,
                const DisplayFrame& shown, const TraceScene& tracer, const std::vector<int>& cachedObjects,
                ViewerUiState& state, ViewerActions& actions) {
    ImGuiIO& io = ImGui::GetIO();
    bool moved = false;
    if (!io.WantCaptureMouse) {
        const float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
        const bool dragged = dx != 0.0f || dy != 0.0f;
        if (ImGui::IsMouseDown(ImGuiMouseButton_Left) && dragged) {
            camera.orbit(-0.3f * dx, 0.3f * dy);
            moved = true;
        }
        if (ImGui::IsMouseDown(ImGuiMouseButton_Right) && dragged) {
            camera.look(0.2f * dx, -0.2f * dy);
            moved = true;
        }
        if (ImGui::IsMouseDown(ImGuiMouseButton_Middle) && dragged) {
            const float s = camera.distance() * 0.0015f;
            camera.fly(0.0f, -dx * s, dy * s);
            moved = true;
        }
        if (io.MouseWheel != 0.0f) {
            camera.zoom(std::pow(0.9f, io.MouseWheel));
            moved = true;
        }
        // A click that did not drag picks the object to inspect.
        if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
            io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < io.MouseDragThreshold * io.MouseDragThreshold &&
            shown.width > 0) {
            int fbw = 0, fbh = 0;
            window.framebufferSize(fbw, fbh);
            const ViewportRect r = fitRect(shown.width, shown.height, fbw, fbh);
            const float scaleX = io.DisplayFramebufferScale.x, scaleY = io.DisplayFramebufferScale.y;
            const float px = (io.MousePos.x * scaleX - static_cast<float>(r.x)) / static_cast<float>(r.width);
            const float py =
                (io.MousePos.y * scaleY - static_cast<float>(fbh - r.y - r.height)) / static_cast<float>(r.height);
            if (px >= 0.0f && px < 1.0f && py >= 0.0f && py < 1.0f) {
                const CameraRays rays(shown.camera, shown.width, shown.height);
                const TraceHit hit = tracer.intersect(rays.ray(static_cast<int>(px * static_cast<float>(shown.width)),
                                                               static_cast<int>(py * static_cast<float>(shown.height))));
                if (hit.hit() && std::find(cachedObjects.begin(), cachedObjects.end(), hit.objectId) != cachedObjects.end()) {
                    state.inspectObject = hit.objectId;
                    state.showInspector = true;
                }
            }
        }
    }
    if (!io.WantCaptureKeyboard) {
        GLFWwindow* w = window.handle();
        const float speed = camera.distance() * 0.8f * dt * (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.0f);
        const auto axis = [&](int plus, int minus) {
            return (glfwGetKey(w, plus) == GLFW_PRESS ? 1.0f : 0.0f) - (glfwGetKey(w, minus) == GLFW_PRESS ? 1.0f : 0.0f);
        };
        const float f = axis(GLFW_KEY_W, GLFW_KEY_S), r = axis(GLFW_KEY_D, GLFW_KEY_A), u = axis(GLFW_KEY_E, GLFW_KEY_Q);
        if (f != 0.0f || r != 0.0f || u != 0.0f) {
            camera.fly(f * speed, r * speed, u * speed);
            moved = true;
        }
    }
    for (int key : keyPresses) {
        if (key == GLFW_KEY_F12) actions.screenshot = true;
        if (io.WantCaptureKeyboard) continue;  // typing into a field
        switch (key) {
        case GLFW_KEY_R: actions.resetCamera = true; break;
        case GLFW_KEY_SPACE: state.playPath = !state.playPath; break;
        case GLFW_KEY_C: actions.clearCaches = true; break;
        case GLFW_KEY_X: state.difference = !state.difference; break;
        case GLFW_KEY_L: state.cacheLevels = !state.cacheLevels; break;
        case GLFW_KEY_TAB: state.showUi = !state.showUi; break;
        case GLFW_KEY_ESCAPE: actions.quit = true; break;
        default: break;
        }
    }
    return moved;
}

std::int64_t pixelsOf(int framebufferWidth, int framebufferHeight, float scale) {
    const auto side = [&](int n) { return std::max(1, static_cast<int>(std::lround(static_cast<float>(n) * scale))); };
    return static_cast<std::int64_t>(side(framebufferWidth)) * side(framebufferHeight);
}

// The film size of the next frame, and under pipeline auto which way makes it.
struct RequestSize {
    int width = 1, height = 1;
    bool reduced = false;           // lowered because the camera moves
    bool showRenderCache = false;   // auto: the Render Cache rather than a full frame
    std::int64_t autoFullPixels = 0, autoRenderCachePixels = 0;  // the sizes auto compared at
};

RequestSize requestSize(const ViewerUiState& state, int fbw, int fbh, bool moving, bool sceneMoves,
                        AutoPipelineRule& autoRule) {
    RequestSize size;
    // Pipeline auto: full frames or the Render Cache (AutoPipelineRule).
    const bool autoPipeline = state.config.pipeline == kAutoPipelineChoice;
    const float movingFactor = moving && state.movingScale < 1.0f ? state.movingScale : 1.0f;
    size.autoFullPixels = pixelsOf(fbw, fbh, state.resolutionScale * movingFactor);
    size.autoRenderCachePixels = pixelsOf(fbw, fbh, state.resolutionScale);
    size.showRenderCache = autoPipeline && autoRule.choose(moving && !state.playPath, !sceneMoves, size.autoFullPixels,
                                                           size.autoRenderCachePixels) == ShownPipeline::RenderCache;
    // The Render Cache reuses the last frame's pixels: a lower resolution
    // while moving would throw them all away.
    const bool showsRenderCache = state.config.pipeline == kRenderCacheChoice || size.showRenderCache;
    size.reduced = moving && state.movingScale < 1.0f && !showsRenderCache;
    const float scale = state.resolutionScale * (size.reduced ? state.movingScale : 1.0f);
    size.width = std::max(1, static_cast<int>(std::lround(static_cast<float>(fbw) * scale)));
    size.height = std::max(1, static_cast<int>(std::lround(static_cast<float>(fbh) * scale)));
    return size;
}

// What the panel and the keys ask the render thread for.
RenderRequest renderRequest(const ViewerUiState& state, const Camera& camera, const RequestSize& size,
                            std::uint64_t clearCount, std::uint64_t pathRestartCount) {
    RenderRequest request;
    request.camera = camera;
    request.width = size.width;
    request.height = size.height;
    request.reducedResolution = size.reduced;
    request.showRenderCache = size.showRenderCache;
    request.config = state.config;
    request.clearCount = clearCount;
    request.playPath = state.playPath;
    request.time = state.animationTime;
    request.pathRestartCount = pathRestartCount;
    request.continuous = state.continuous;
    request.difference = state.difference;
    request.differenceGain = state.differenceGain;
    request.renderCacheOverlay = state.renderCacheOverlay;
    request.renderCacheAsync = state.renderCacheAsync;
    request.cacheLevels = state.cacheLevels;
    request.inspectObject = state.showInspector ? state.inspectObject : -1;
    request.inspectorFaceSize = state.inspectorFaceSize;
    return request;
}

// The frame fitted into the window, on a dark background.
void drawFrame(const GlTexture& frameTexture, int fbw, int fbh) {
    glViewport(0, 0, fbw, fbh);
    glClearColor(0.05f, 0.05f, 0.05f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    frameTexture.blitTo(fitRect(frameTexture.width(), frameTexture.height(), fbw, fbh));
}

// A shown frame's render time teaches pipeline auto's rule what each way
// costs. Left out: a Render Cache frame that traced every pixel (its first,
// a cut) and a full frame made while the Render Cache waited for samples
// (its time holds the Render Cache's reconstruction too), and a complete
// refinement shown again (nothing was rendered).
void teachAutoRule(const DisplayFrame& shown, AutoPipelineRule& rule) {
    if (!shown.autoPipeline || shown.renderCachePriming || shown.refinementReused) return;
    if (shown.shown == ShownPipeline::RenderCache && shown.stats.renderCache && shown.stats.renderCache->refreshedAll)
        return;
    rule.observe(shown.shown, shown.renderMs, static_cast<std::int64_t>(shown.width) * shown.height);
}

// Writes the window as a screenshot when a scripted run ends with one, or
// when F12 asked (where a failure does not end the session).
void writeScreenshotIfAsked(bool scripted, bool asked, const std::string& optionPath, const std::string& sceneName,
                            int& counter, int fbw, int fbh, std::ostream& out) {
    if (!asked) return;
    const std::filesystem::path path = scripted || !optionPath.empty() ? std::filesystem::path(optionPath)
                                                                       : nextScreenshotPath(sceneName, counter);
    if (scripted) {
        writeScreenshot(fbw, fbh, path);  // a failure fails the run
        out << "screenshot " << path.string() << " (" << fbw << "x" << fbh << ")" << std::endl;
        return;
    }
    // A key press must not end an interactive session.
    try {
        writeScreenshot(fbw, fbh, path);
        out << "screenshot " << path.string() << " (" << fbw << "x" << fbh << ")" << std::endl;
    } catch (const std::exception& e) {
        out << "screenshot not written: " << e.what() << std::endl;
    }
}

// A scripted run's line for one shown frame.
void printScriptedFrame(const DisplayFrame& shown, int frames, double intervalMs, const UiThreadTimes& uiTimes,
                        std::ostream& out) {
    FrameResult result;
    result.frame = shown.pathFrame;
    result.milliseconds = shown.renderMs;
    result.stats = shown.stats;
    out << formatFrameLine(result, frames) << "  | interval " << formatFixed(intervalMs, 1) << " encode "
        << formatFixed(shown.encodeMs, 2) << " upload " << formatFixed(uiTimes.uploadMs, 2) << " ui "
        << formatFixed(uiTimes.uiMs, 2) << " present " << formatFixed(uiTimes.presentMs, 2) << " ms";
    if (shown.autoPipeline) out << " | auto: " << shownPipelineName(shown.shown);
    if (shown.refinementTarget > 0)
        out << " | spp " << shown.refinedSamples << "/" << shown.refinementTarget
            << (shown.refinedSamples == 0 ? " (the plain frame)" : "");
    if (shown.asyncRenderCache && shown.stats.renderCache)
        out << " | async: merged " << shown.mergedSamples << " samples, tracer "
            << formatFixed(shown.samplesPerSecond / 1.0e6, 3) << " Msamples/s, busy "
            << formatFixed(100.0 * shown.traceBusyShare, 0) << " %, request map " << shown.stats.renderCache->budget
            << " rays, reshading 1 in " << shown.reshadeInterval;
    out << std::endl;
}

}  // namespace

Viewer::Viewer(RenderJob job, const ViewerRenderConfig& config, const ViewerOptions& options)
    : job_(std::move(job)), config_(config), options_(options) {}

ViewerUiState Viewer::startingUiState() const {
    ViewerUiState state;
    state.config = config_;
    state.movingScale = options_.movingScale;
    state.showUi = !options_.hideUi;
    state.playPath = options_.scriptedFrames.has_value();
    state.difference = options_.difference;
    state.cacheLevels = options_.cacheLevels;
    state.renderCacheAsync = options_.renderCacheDisplay == RenderCacheDisplay::Async;
    if (options_.inspectObject) {
        state.inspectObject = *options_.inspectObject;
        state.showInspector = true;
    }
    return state;
}

RenderWorkerSetup Viewer::workerSetup(const TraceScene& tracer) const {
    RenderWorkerSetup setup;
    setup.scene = &job_.scene;
    setup.tracer = &tracer;
    setup.path = job_.path;
    setup.timeline = job_.timeline;
    setup.base = job_.settings;
    setup.display = job_.display;
    setup.scriptedFrames = options_.scriptedFrames;
    setup.renderCacheTraceThreads = options_.renderCacheTraceThreads;
    setup.renderCacheDisplayThreads = options_.renderCacheDisplayThreads;
    setup.renderCacheRequestFrames = options_.renderCacheRequestFrames;
    setup.renderCacheReshadeMs = options_.renderCacheReshadeMs;
    setup.samplesPerPixel = options_.samplesPerPixel;
    setup.onPublished = &ViewerWindow::wake;
    return setup;
}

void Viewer::run(std::ostream& out) {
    const Scene& scene = job_.scene;
    const bool scripted = options_.scriptedFrames.has_value();
    const int frames = options_.scriptedFrames.value_or(0);
    const RenderSettings& base = job_.settings;

    ViewerWindow window(base.width, base.height, ("raycache view: " + scene.name).c_str(),
                        options_.vsync && !scripted);
    const TraceScene tracer(scene);
    FrameHandoff handoff;
    GlTexture frameTexture, inspectorTexture;

    ViewerUiState state = startingUiState();
    ViewerCamera camera(job_.path.cameraAt(scene.camera, 0));
    std::uint64_t clearCount = 0, pathRestartCount = 0;
    Clock::time_point lastMotion = Clock::now() - std::chrono::seconds(1);
    int screenshotCounter = 0;

    std::vector<int> cachedObjects = cachedObjectsUnder(scene, base, state.config);
    ViewerRenderConfig cachedObjectsConfig = state.config;

    FrameTimeHistory intervals, renderTimes;
    UiThreadTimes uiTimes;
    AutoPipelineRule autoRule(options_.targetFrameMs);
    std::int64_t autoFullPixels = 0, autoRenderCachePixels = 0;
    std::vector<ScriptedSample> samples;
    Clock::time_point lastShown{};
    double lastIntervalMs = 0.0;
    bool anyShown = false;
    bool screenshotPending = false;
    DisplayFrame shown;

    RenderWorker worker(workerSetup(tracer), handoff);

    if (scripted)
        out << "scene " << scene.name << ": " << scene.objects.size() << " objects, " << scene.lights.size()
            << " lights, " << base.width << "x" << base.height << ", " << frames << " frames (view, scripted)\n";

    Clock::time_point lastLoop = Clock::now();
    while (!window.closeRequested()) {
        // Sleep until input, a finished frame, or a UI tick (held keys fly the camera).
        window.waitEvents(1.0 / 60.0);
        if (const std::exception_ptr error = worker.error()) std::rethrow_exception(error);
        const Clock::time_point now = Clock::now();
        const float dt = static_cast<float>(std::chrono::duration<double>(now - lastLoop).count());
        lastLoop = now;

        // 1. The newest finished frame, if any, onto the GPU.
        const bool newFrame = handoff.take(shown);
        if (newFrame) {
            const Clock::time_point t0 = Clock::now();
            frameTexture.upload(shown.rgba, shown.width, shown.height);
            if (shown.inspectedObject >= 0)
                inspectorTexture.upload(shown.inspectorRgba, shown.inspectorWidth, shown.inspectorHeight);
            uiTimes.uploadMs = msBetween(t0, Clock::now());
            lastIntervalMs = anyShown ? msBetween(lastShown, t0) : 0.0;
            if (anyShown) intervals.add(lastIntervalMs);
            renderTimes.add(shown.renderMs);
            teachAutoRule(shown, autoRule);
            lastShown = t0;
            anyShown = true;
        }

        // 2. Input and panel.
        const Clock::time_point uiStart = Clock::now();
        const std::vector<int> keyPresses = window.takeKeyPresses();
        window.beginUiFrame();
        ViewerActions actions;
        const bool moved = !scripted && applyInput(window, camera, dt, keyPresses, shown, tracer, cachedObjects,
                                                   state, actions);
        const bool wasPlaying = state.playPath;
        if (state.showUi) {
            ViewerPanelInput in{&scene,         &shown,          &intervals,  &renderTimes,
                                uiTimes,        cachedObjects,   inspectorTexture.id(),
                                inspectorTexture.width(),        inspectorTexture.height(),
                                &autoRule,      autoFullPixels,  autoRenderCachePixels};
            drawViewerPanel(in, state, actions);
        }

        // 3. What to render next.
        if (moved && state.playPath) state.playPath = false;  // the user takes the camera
        if (wasPlaying && !state.playPath && shown.pathFrame >= 0 && !moved) camera.setCamera(shown.camera);
        bool cameraMoved = moved;
        if (actions.resetCamera) {
            camera = ViewerCamera(job_.path.cameraAt(scene.camera, 0));
            state.playPath = false;
            cameraMoved = true;
        }
        if (actions.restartPath) {
            ++pathRestartCount;
            state.playPath = true;
        }
        if (actions.clearCaches) ++clearCount;
        if (actions.quit) window.requestClose();
        if (cameraMoved) lastMotion = now;
        if (!(state.config == cachedObjectsConfig)) {
            cachedObjects = cachedObjectsUnder(scene, base, state.config);
            cachedObjectsConfig = state.config;
        }

        const bool moving = std::chrono::duration<double>(now - lastMotion).count() < kMovingHoldSeconds;
        int fbw = 0, fbh = 0;
        window.framebufferSize(fbw, fbh);
        if (!scene.animation.empty() && state.playAnimation && !scripted)
            state.animationTime += dt * state.animationSpeed;
        RequestSize size;
        if (scripted) {
            size.width = base.width;
            size.height = base.height;
        } else {
            size = requestSize(state, fbw, fbh, moving, !scene.animation.empty(), autoRule);
            autoFullPixels = size.autoFullPixels;
            autoRenderCachePixels = size.autoRenderCachePixels;
        }
        const RenderRequest request = renderRequest(state, camera.camera(), size, clearCount, pathRestartCount);
        if (fbw > 0 && fbh > 0) worker.submit(request);

        // 4. Draw: the frame, then the panel over it.
        drawFrame(frameTexture, fbw, fbh);
        window.endUiFrame();
        uiTimes.uiMs = msBetween(uiStart, Clock::now());

        const bool lastScriptedFrame = scripted && newFrame && shown.pathFrame == frames - 1;
        if (actions.screenshot) screenshotPending = true;
        const bool screenshot =
            (screenshotPending && !scripted && anyShown) || (lastScriptedFrame && !options_.screenshotPath.empty());
        writeScreenshotIfAsked(scripted, screenshot, options_.screenshotPath, scene.name, screenshotCounter, fbw, fbh,
                               out);
        if (screenshot) screenshotPending = false;
        const Clock::time_point presentStart = Clock::now();
        window.swapBuffers();
        glFinish();  // the swap is asynchronous: count the GPU's work in this frame's present time
        uiTimes.presentMs = msBetween(presentStart, Clock::now());

        if (scripted && newFrame) {
            samples.push_back({lastIntervalMs, shown.renderMs, shown.encodeMs, uiTimes.uploadMs, uiTimes.uiMs,
                               uiTimes.presentMs, shown.asyncRenderCache ? shown.samplesPerSecond : -1.0});
            printScriptedFrame(shown, frames, lastIntervalMs, uiTimes, out);
            if (lastScriptedFrame) break;
        }
    }
    if (scripted && !samples.empty()) printScriptedSummary(samples, std::min(options_.warmupFrames, frames - 1), out);
}

}  // namespace raycache
