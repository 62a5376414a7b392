#include "viewer/ViewerPanel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <imgui.h>
#include <string>

#include "viewer/CacheLevelOverlayImage.h"
#include "viewer/PipelineChoice.h"
#include "viewer/RenderCacheOverlayImage.h"
#include "viewer/TechniqueChoice.h"

namespace raycache {

namespace {

constexpr std::array kFaceResolutions = {0, 64, 128, 256, 512, 1024};  // 0: the scene's own

void drawCameraSection(const ViewerPanelInput& in, ViewerUiState& state, ViewerActions& actions) {
    if (!ImGui::CollapsingHeader("Camera")) return;
    ImGui::TextWrapped("Left drag: orbit   right drag: look   middle drag: pan   wheel: zoom   "
                       "WASD/QE: fly (shift: faster)   click: inspect an object's cache");
    if (ImGui::Button("Reset (R)")) actions.resetCamera = true;
    ImGui::SameLine();
    if (ImGui::Button(state.playPath ? "Pause path (space)" : "Play path (space)")) state.playPath = !state.playPath;
    ImGui::SameLine();
    if (ImGui::Button("Restart path")) actions.restartPath = true;
    const Camera& c = in.frame->camera;
    if (in.frame->pathFrame >= 0) ImGui::Text("path frame %d", in.frame->pathFrame);
    ImGui::Text("position %.2f %.2f %.2f  looking at %.2f %.2f %.2f", static_cast<double>(c.position.x),
                static_cast<double>(c.position.y), static_cast<double>(c.position.z), static_cast<double>(c.lookAt.x),
                static_cast<double>(c.lookAt.y), static_cast<double>(c.lookAt.z));
}

void drawAnimationSection(const ViewerPanelInput& in, ViewerUiState& state) {
    const SceneAnimation& animation = in.scene->animation;
    if (animation.empty() || !ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::Button(state.playAnimation ? "Pause" : "Play")) state.playAnimation = !state.playAnimation;
    ImGui::SameLine();
    if (ImGui::Button("Restart")) state.animationTime = 0.0f;
    // Scrubbing pauses: the slider would fight the running clock.
    const float longest = std::max(animation.duration(), 0.1f);
    float shown = std::fmod(state.animationTime, longest);
    if (ImGui::SliderFloat("time (s)", &shown, 0.0f, longest, "%.2f")) {
        state.animationTime = shown;
        state.playAnimation = false;
    }
    ImGui::SliderFloat("speed", &state.animationSpeed, 0.05f, 4.0f, "%.2fx", ImGuiSliderFlags_Logarithmic);
    if (const auto& u = in.frame->stats.sceneUpdate)
        ImGui::Text("update %.2f ms: %d objects, %d lights changed, %lld texels invalidated", u->milliseconds,
                    u->objectsChanged, u->lightsChanged, static_cast<long long>(u->texelsInvalidated));
}

// --spp N: how far the still view's anti-aliasing has come.
void drawRefinementLine(const DisplayFrame& f) {
    if (f.refinementTarget == 0) return;
    if (f.refinedSamples == 0)
        ImGui::Text("anti-aliasing: waits for the camera to stop (%d samples per pixel then)", f.refinementTarget);
    else if (f.refinedSamples < f.refinementTarget)
        ImGui::Text("anti-aliasing: %d of %d samples per pixel", f.refinedSamples, f.refinementTarget);
    else
        ImGui::Text("anti-aliased: %d samples per pixel", f.refinementTarget);
}

// Pipeline auto: which way made the frame on screen, and the estimates the
// choice was made from.
void drawAutoPipelineLine(const ViewerPanelInput& in) {
    const DisplayFrame& f = *in.frame;
    if (!f.autoPipeline) return;
    ImGui::Text("auto: showing %s%s", shownPipelineName(f.shown),
                f.renderCachePriming ? " (the Render Cache's samples are on their way)" : "");
    if (!in.autoRule) return;
    const double full = in.autoRule->estimateMs(ShownPipeline::FullFrame, in.autoFullPixels);
    const double renderCache = in.autoRule->estimateMs(ShownPipeline::RenderCache, in.autoRenderCachePixels);
    const auto ms = [](double v) {
        char text[32] = "not measured";
        if (v >= 0.0) std::snprintf(text, sizeof text, "%.1f", v);
        return std::string(text);
    };
    ImGui::Text("  estimated ms: full frame %s, render cache %s; target %.1f", ms(full).c_str(),
                ms(renderCache).c_str(), in.autoRule->targetMs());
}

void drawRenderingSection(const ViewerPanelInput& in, ViewerUiState& state, ViewerActions& actions) {
    if (!ImGui::CollapsingHeader("Rendering", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ViewerRenderConfig& config = state.config;
    const char* technique = kTechniqueChoices[static_cast<std::size_t>(config.technique)].label;
    if (ImGui::BeginCombo("technique", technique)) {
        for (std::size_t i = 0; i < kTechniqueChoices.size(); ++i)
            if (ImGui::Selectable(kTechniqueChoices[i].label, static_cast<int>(i) == config.technique))
                config.technique = static_cast<int>(i);
        ImGui::EndCombo();
    }
    if (ImGui::BeginCombo("pipeline", kPipelineChoices[static_cast<std::size_t>(config.pipeline)].label)) {
        for (std::size_t i = 0; i < kPipelineChoices.size(); ++i)
            if (ImGui::Selectable(kPipelineChoices[i].label, static_cast<int>(i) == config.pipeline))
                config.pipeline = static_cast<int>(i);
        ImGui::EndCombo();
    }
    drawAutoPipelineLine(in);
    drawRefinementLine(*in.frame);
    if (ImGui::BeginCombo("accelerator", acceleratorName(config.accelerator))) {
        for (const Accelerator a : kAccelerators)
            if (ImGui::Selectable(acceleratorName(a), a == config.accelerator)) config.accelerator = a;
        ImGui::EndCombo();
    }
    const int resolution = config.cacheResolution.value_or(0);
    const std::string resolutionLabel = resolution == 0 ? "scene" : std::to_string(resolution);
    if (ImGui::BeginCombo("face resolution", resolutionLabel.c_str())) {
        for (int r : kFaceResolutions) {
            const std::string label = r == 0 ? "scene" : std::to_string(r);
            if (ImGui::Selectable(label.c_str(), r == resolution))
                config.cacheResolution = r == 0 ? std::nullopt : std::optional<int>(r);
        }
        ImGui::EndCombo();
    }
    // CDCT search: edited as a pair, applied when valid (epsilon < step).
    float step = config.cdctStep.value_or(0.4f);
    float epsilon = config.cdctEpsilon.value_or(0.05f);
    bool cdctEdited = ImGui::InputFloat("CDCT step (delta)", &step, 0.05f, 0.5f, "%.3f");
    cdctEdited |= ImGui::InputFloat("CDCT epsilon", &epsilon, 0.005f, 0.05f, "%.4f");
    if (cdctEdited) {
        config.cdctStep = std::max(step, 1e-4f);
        config.cdctEpsilon = std::max(epsilon, 1e-5f);
    }
    ImGui::SliderInt("max depth", &config.maxDepth, 1, 16);
    ImGui::SliderFloat("resolution scale", &state.resolutionScale, 0.1f, 1.0f, "%.2f");
    ImGui::SliderFloat("while moving", &state.movingScale, 0.1f, 1.0f, "%.2f");
    ImGui::Checkbox("render continuously", &state.continuous);
    if (ImGui::Button("Clear caches (C)")) actions.clearCaches = true;
    ImGui::SameLine();
    if (ImGui::Button("Screenshot (F12)")) actions.screenshot = true;
    if (!in.frame->configError.empty())
        ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "not applied: %s", in.frame->configError.c_str());
}

constexpr double kMiB = 1024.0 * 1024.0;

// Every cube of the frame: its object, finest face resolution, levels,
// memory (all levels) and this frame's hits per level; the first row sums
// them. Clipped to the visible rows, for scenes of very many cubes.
void drawCubeTable(const FrameCacheStats& c) {
    const int levels = c.levels();
    const int columns = 6 + levels;
    constexpr int kVisibleRows = 8;
    const auto rows = static_cast<int>(c.objects.size()) + 1;
    const float height = ImGui::GetFrameHeightWithSpacing() * static_cast<float>(std::min(rows, kVisibleRows) + 1);
    if (!ImGui::BeginTable("cubes", columns,
                           ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit |
                               ImGuiTableFlags_ScrollX | ImGuiTableFlags_ScrollY,
                           ImVec2(0.0f, height)))
        return;
    ImGui::TableSetupScrollFreeze(1, 1);  // the names and the header stay in view
    ImGui::TableSetupColumn("object");
    ImGui::TableSetupColumn("finest");
    ImGui::TableSetupColumn("levels");
    ImGui::TableSetupColumn("MiB");
    // The cache policy (docs/caching.md, "Caching that never costs").
    ImGui::TableSetupColumn("policy");
    ImGui::TableSetupColumn("saves/costs (rays)");
    for (int k = 0; k < levels; ++k) ImGui::TableSetupColumn(("L" + std::to_string(k)).c_str());
    ImGui::TableHeadersRow();
    ImGuiListClipper clipper;
    clipper.Begin(rows);
    while (clipper.Step())
        for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
            ImGui::TableNextRow();
            if (row == 0) {
                ImGui::TableNextColumn();
                ImGui::Text("all (%zu)", c.objects.size());
                ImGui::TableNextColumn();
                ImGui::TableNextColumn();
                ImGui::TableNextColumn();
                ImGui::Text("%.2f", static_cast<double>(c.bytes()) / kMiB);
                ImGui::TableNextColumn();
                ImGui::Text("%d aside", c.bypassedCubes());
                ImGui::TableNextColumn();
                for (int k = 0; k < levels; ++k) {
                    ImGui::TableNextColumn();
                    ImGui::Text("%llu", static_cast<unsigned long long>(c.hitsAtLevel(k)));
                }
                continue;
            }
            const ObjectCacheStats& o = c.objects[static_cast<std::size_t>(row - 1)];
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(o.name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%d^2", o.resolution);
            ImGui::TableNextColumn();
            ImGui::Text("%d", o.levels);
            ImGui::TableNextColumn();
            ImGui::Text("%.2f", static_cast<double>(o.bytes) / kMiB);
            ImGui::TableNextColumn();
            ImGui::Text("%s (%llu/%llu/%llu)", cubeStateName(o.state),
                        static_cast<unsigned long long>(o.framesCaching),
                        static_cast<unsigned long long>(o.framesSampling),
                        static_cast<unsigned long long>(o.framesBypassed));
            ImGui::TableNextColumn();
            if (o.state == CubeState::Bypassed) ImGui::TextDisabled("-");
            else ImGui::Text("%.0f / %.0f", o.policySaving, o.policyCost);
            for (int k = 0; k < levels; ++k) {
                ImGui::TableNextColumn();
                if (k < o.levels)
                    ImGui::Text("%llu", static_cast<unsigned long long>(o.hitsByLevel[static_cast<std::size_t>(k)]));
                else
                    ImGui::TextDisabled("-");
            }
        }
    ImGui::EndTable();
}

void drawStatisticsSection(const ViewerPanelInput& in) {
    if (!ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const DisplayFrame& f = *in.frame;
    const RayCounts& r = f.stats.rays;
    ImGui::Text("rays: primary %llu  shadow %llu", static_cast<unsigned long long>(r.primary),
                static_cast<unsigned long long>(r.shadow));
    ImGui::Text("      reflection %llu  refraction %llu", static_cast<unsigned long long>(r.reflection),
                static_cast<unsigned long long>(r.refraction));
    const double mrays = f.renderMs > 0.0 ? static_cast<double>(r.total()) / (f.renderMs * 1e3) : 0.0;
    ImGui::Text("      total %llu  %.2f Mrays/s", static_cast<unsigned long long>(r.total()), mrays);
    if (f.stats.cache && !f.stats.cache->objects.empty()) {
        const FrameCacheStats& c = *f.stats.cache;
        const double hitRate = c.lookups() ? 100.0 * static_cast<double>(c.hits()) / static_cast<double>(c.lookups()) : 0.0;
        ImGui::Text("cache: %zu cubes, hits %.1f%% of %llu lookups, stores %llu", c.objects.size(), hitRate,
                    static_cast<unsigned long long>(c.lookups()), static_cast<unsigned long long>(c.stores()));
        ImGui::Text("       invalid texels %.1f%% (before the frame), memory %.1f MiB", c.invalidPercentBefore(),
                    static_cast<double>(f.cacheBytes) / kMiB);
        if (c.tracedAsUncached)
            ImGui::Text("       policy: all %zu cubes bypassed: the frame was rendered as uncached", c.objects.size());
        else if (c.bypassedCubes() || c.samplingCubes())
            ImGui::Text("       policy: of %zu cubes %d bypassed, %d sampling (%llu rays traced directly)",
                        c.objects.size(), c.bypassedCubes(), c.samplingCubes(),
                        static_cast<unsigned long long>(c.bypassedRays()));
        if (ImGui::TreeNodeEx("every cube: memory, policy (frames caching/sampling/bypassed), hits per level (L0 finest) this frame",
                              ImGuiTreeNodeFlags_DefaultOpen)) {
            drawCubeTable(c);
            ImGui::TreePop();
        }
    } else {
        ImGui::TextUnformatted("cache: none (no object caches under this technique)");
    }
}

void drawRenderCacheSection(const ViewerPanelInput& in, ViewerUiState& state) {
    const DisplayFrame& f = *in.frame;
    if (!f.stats.renderCache || !ImGui::CollapsingHeader("Render cache", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const RenderCacheStats& c = *f.stats.renderCache;
    const double pixels = static_cast<double>(std::max<std::int64_t>(1, c.pixels));
    ImGui::Checkbox("display at its own rate (async; scenes that move: sync)", &state.renderCacheAsync);
    // Both rates: how often the display makes an image, and how fast the
    // samples it is made of come.
    if (f.asyncRenderCache) {
        ImGui::Text("display async (%d display + %d trace threads): %.1f fps", f.displayThreads, f.traceThreads,
                    f.displayFps);
        ImGui::Text("tracer: %.3f Msamples/s, %.1f batches/s, %.1f requests/s, busy %.0f%%", f.samplesPerSecond / 1.0e6,
                    f.batchesPerSecond, f.requestsPerSecond, 100.0 * f.traceBusyShare);
        ImGui::Text("merged %lld samples, request map %lld rays", static_cast<long long>(f.mergedSamples),
                    static_cast<long long>(c.budget));
        ImGui::Text("reshading: one in %d mirror/glass samples a moving frame (--render-cache-reshade-ms)",
                    f.reshadeInterval);
    } else {
        ImGui::Text("display sync (one request map traced per frame): %.1f fps, %.3f Msamples/s", in.intervals->fps(),
                    in.intervals->fps() * static_cast<double>(c.fresh + c.predicted) / 1.0e6);
    }
    ImGui::Text("traced %.1f%% + %lld predicted, holes %.1f%%, reshaded %lld", 100.0 * static_cast<double>(c.fresh) / pixels,
                static_cast<long long>(c.predicted), 100.0 * static_cast<double>(c.holes) / pixels,
                static_cast<long long>(c.reshaded));
    ImGui::Text("ms: reconstruction %.1f (reproject %.1f, maps %.1f, filters %.1f)", c.reconstructionMs(), c.reprojectMs,
                c.mapsMs, c.filterMs);
    ImGui::Text("    samples %.1f (trace %.1f, reshade %.1f)", c.sampleGenerationMs(), c.traceMs, c.reshadeMs);
    // A model of the passes' reads and writes (rendercache/ReconstructionBytes.h), not measured traffic.
    ImGui::Text("reconstruction moves %.0f MB counted, %.1f GB/s", static_cast<double>(c.reconstructionBytes()) / 1.0e6,
                c.reconstructionGbPerSecond());
    ImGui::RadioButton("no overlay", &state.renderCacheOverlay, static_cast<int>(RenderCacheOverlay::None));
    ImGui::SameLine();
    ImGui::RadioButton("pixel sources", &state.renderCacheOverlay, static_cast<int>(RenderCacheOverlay::Sources));
    ImGui::SameLine();
    ImGui::RadioButton("request map", &state.renderCacheOverlay, static_cast<int>(RenderCacheOverlay::Requests));
    if (state.renderCacheOverlay == static_cast<int>(RenderCacheOverlay::Sources))
        ImGui::TextDisabled("green fresh, yellow 3x3, orange 7x7, red unfilled, magenta culled");
    else if (state.renderCacheOverlay == static_cast<int>(RenderCacheOverlay::Requests))
        ImGui::TextDisabled("blue: tile priority (holes, old samples); white: requested pixels");
}

void drawDifferenceSection(const ViewerPanelInput& in, ViewerUiState& state) {
    if (!ImGui::CollapsingHeader("Difference to the uncached image", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Checkbox("show heat map (X)", &state.difference);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120.0f);
    ImGui::SliderFloat("gain", &state.differenceGain, 1.0f, 32.0f, "x%.0f", ImGuiSliderFlags_Logarithmic);
    if (in.frame->showsDifference)
        ImGui::Text("mean |difference| %.5f  (blue = same, red = totally different)", in.frame->meanDifference);
}

// The cube-level overlay's switch and legend: each record value's colour
// and share of the frame's pixels.
void drawCacheLevelOverlay(const ViewerPanelInput& in, ViewerUiState& state) {
    ImGui::Checkbox("cube level per pixel (L)", &state.cacheLevels);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("what the cache did for each pixel's weightiest ray leaving a caching object "
                          "(docs/viewer.md)");
    if (!state.cacheLevels) return;
    const DisplayFrame& f = *in.frame;
    if (!f.showsCacheLevels) {
        if (state.difference) ImGui::TextDisabled("hidden while the difference view is on");
        else if (f.stats.renderCache) ImGui::TextDisabled("not recorded by the Render Cache pipeline");
        else ImGui::TextDisabled("from the next frame");
        return;
    }
    const int levels = f.stats.cache ? f.stats.cache->levels() : 1;
    double pixels = 0.0;
    for (const std::int64_t n : f.cacheLevelPixels) pixels += static_cast<double>(n);
    pixels = std::max(pixels, 1.0);
    for (int value = CacheLevelImage::kNoCachingRay; value < levels; ++value) {
        const std::array<std::uint8_t, 3> c = cacheLevelColor(static_cast<std::int8_t>(value));
        const ImVec4 color(static_cast<float>(c[0]) / 255.0f, static_cast<float>(c[1]) / 255.0f,
                           static_cast<float>(c[2]) / 255.0f, 1.0f);
        const std::string id = "##level" + std::to_string(value);
        ImGui::ColorButton(id.c_str(), color, ImGuiColorEditFlags_NoTooltip, ImVec2(12.0f, 12.0f));
        ImGui::SameLine();
        const double share =
            100.0 * static_cast<double>(f.cacheLevelPixels[static_cast<std::size_t>(value + 2)]) / pixels;
        if (value == CacheLevelImage::kNoCachingRay) ImGui::Text("no caching object  %.1f%%", share);
        else if (value == CacheLevelImage::kTraced) ImGui::Text("traced (miss or rejected)  %.1f%%", share);
        else if (value == 0) ImGui::Text("level 0 (finest)  %.1f%%", share);
        else ImGui::Text("level %d (1/%d per side)  %.1f%%", value, 1 << value, share);
    }
}

void drawInspector(const ViewerPanelInput& in, ViewerUiState& state) {
    if (!ImGui::CollapsingHeader("Cache inspector", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (in.cachedObjects.empty()) {
        ImGui::TextUnformatted("no caching objects under this technique");
        return;
    }
    drawCacheLevelOverlay(in, state);
    const auto nameOf = [&](int id) {
        return id >= 0 ? in.scene->objects[static_cast<std::size_t>(id)].name.c_str() : "(none)";
    };
    if (ImGui::BeginCombo("object", nameOf(state.inspectObject))) {
        if (ImGui::Selectable("(none)", state.inspectObject < 0)) state.inspectObject = -1;
        for (int id : in.cachedObjects)
            if (ImGui::Selectable(nameOf(id), id == state.inspectObject)) state.inspectObject = id;
        ImGui::EndCombo();
    }
    state.showInspector = state.inspectObject >= 0;
    if (in.frame->stats.cache)
        for (const ObjectCacheStats& o : in.frame->stats.cache->objects)
            if (o.objectId == state.inspectObject)
                ImGui::Text("%d^2 per face, hits %llu of %llu, stores %llu, %.1f MiB", o.resolution,
                            static_cast<unsigned long long>(o.hits), static_cast<unsigned long long>(o.lookups),
                            static_cast<unsigned long long>(o.stores),
                            static_cast<double>(o.bytes) / kMiB);
}

void drawInspectorWindow(const ViewerPanelInput& in, ViewerUiState& state) {
    if (!state.showInspector || in.frame->inspectedObject < 0 || in.inspectorWidth == 0) return;
    // Bottom right, clear of the panel and of the middle of the view.
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowSize(ImVec2(360.0f, 300.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowPos(ImVec2(display.x - 370.0f, display.y - 310.0f), ImGuiCond_FirstUseEver);
    const std::string title =
        "Cube of " + in.scene->objects[static_cast<std::size_t>(in.frame->inspectedObject)].name + "###inspector";
    if (ImGui::Begin(title.c_str(), &state.showInspector)) {
        ImGui::Text("invalid texels %.2f%% (black)", in.frame->inspectedInvalidPercent);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("+Y above +Z; -X, +Z, +X, -Z in the middle row; -Y below +Z");
        if (in.scene && !in.scene->animation.empty()) {
            ImGui::Text("dropped by the last change: %lld (magenta; half magenta once filled again)",
                        static_cast<long long>(in.frame->inspectedDroppedTexels));
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("texels whose ray trees the last move of an object or light could reach "
                                  "(docs/dynamic-scenes.md)");
        }
        const float width = std::max(ImGui::GetContentRegionAvail().x, 64.0f);
        const float height = width * static_cast<float>(in.inspectorHeight) / static_cast<float>(in.inspectorWidth);
        ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(in.inspectorTexture)),
                     ImVec2(width, height));
    }
    ImGui::End();
    if (!state.showInspector) state.inspectObject = -1;
}

}  // namespace

void drawViewerPanel(const ViewerPanelInput& in, ViewerUiState& state, ViewerActions& actions) {
    ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(400.0f, 0.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (ImGui::Begin("raycache")) {
        const DisplayFrame& f = *in.frame;
        ImGui::Text("%s: %zu objects, %zu lights", in.scene->name.c_str(), in.scene->objects.size(),
                    in.scene->lights.size());
        ImGui::Text("%.1f fps  %.1f ms/frame   %dx%d%s", in.intervals->fps(), in.intervals->medianMs(), f.width,
                    f.height, f.reducedResolution ? " (moving)" : "");
        const std::vector<float> times = in.intervals->chronological();
        const float top = std::max(33.4f, static_cast<float>(in.intervals->maxMs()) * 1.1f);
        ImGui::PlotLines("##frametimes", times.data(), static_cast<int>(times.size()), 0, "frame time (ms)", 0.0f, top,
                         ImVec2(ImGui::GetContentRegionAvail().x, 60.0f));
        ImGui::Text("render %.1f  encode %.1f  diff %.1f | upload %.2f  ui %.2f  present %.2f ms", f.renderMs,
                    f.encodeMs, f.differenceMs, in.uiTimes.uploadMs, in.uiTimes.uiMs, in.uiTimes.presentMs);
        drawStatisticsSection(in);
        drawRenderingSection(in, state, actions);
        drawCameraSection(in, state, actions);
        drawAnimationSection(in, state);
        drawRenderCacheSection(in, state);
        drawDifferenceSection(in, state);
        drawInspector(in, state);
        ImGui::TextDisabled("Tab: hide panel   Esc: quit");
    }
    ImGui::End();
    drawInspectorWindow(in, state);
}

}  // namespace raycache
