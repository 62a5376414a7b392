#pragma once
// The rendering pipelines the viewer's combo offers, and how each one is
// set in RenderSettings. The viewer's hybrid pipeline takes its G-buffer from
// primary-ray packets: the window already owns the process's OpenGL context
// (GLFW), and a second, headless EGL context on the render thread is not
// something every driver stack allows next to it.
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
};

// The index of the Render Cache in kPipelineChoices.
inline constexpr int kRenderCacheChoice = 2;

}  // namespace raycache
