#pragma once
// The rendering pipelines the viewer's combo offers, and how each one is
// set in RenderSettings. The viewer's hybrid pipeline takes its G-buffer from
// primary-ray packets: the window already owns the process's OpenGL context
// (GLFW), and a second, headless EGL context on the render thread is not
// something every driver stack allows next to it.
//
// *auto* renders full frames with the ray pipeline and shows the Render Cache
// (at its own rate, or synchronously, as --render-cache-display says) while
// the camera moves faster than full frames can follow (AutoPipelineRule).
#include <array>

#include "render/RenderSettings.h"

namespace raycache {

struct PipelineChoice {
    const char* label;
    void (*apply)(RenderSettings&);
};

inline constexpr std::array kPipelineChoices = {
    PipelineChoice{"ray", [](RenderSettings& s) { s.pipeline = PipelineKind::Ray; }},
    PipelineChoice{"hybrid (packet G-buffer)",
                   [](RenderSettings& s) {
                       s.pipeline = PipelineKind::Hybrid;
                       s.gbuffer = GBufferSource::Packets;
                   }},
    PipelineChoice{"render cache", [](RenderSettings& s) { s.pipeline = PipelineKind::RenderCache; }},
    PipelineChoice{"auto (full frames or render cache)", [](RenderSettings& s) { s.pipeline = PipelineKind::Ray; }},
};

// The index of the Render Cache and of auto in kPipelineChoices.
inline constexpr int kRenderCacheChoice = 2;
inline constexpr int kAutoPipelineChoice = 3;

// `view --pipeline`: the choices by the names the command line takes.
enum class ViewerPipeline { Ray = 0, Hybrid = 1, RenderCache = kRenderCacheChoice, Auto = kAutoPipelineChoice };

inline constexpr std::array kViewerPipelines{ViewerPipeline::Auto, ViewerPipeline::Ray, ViewerPipeline::Hybrid,
                                             ViewerPipeline::RenderCache};

inline const char* viewerPipelineName(ViewerPipeline p) {
    switch (p) {
    case ViewerPipeline::Ray: return "ray";
    case ViewerPipeline::Hybrid: return "hybrid";
    case ViewerPipeline::RenderCache: return "render-cache";
    case ViewerPipeline::Auto: break;
    }
    return "auto";
}

}  // namespace raycache
