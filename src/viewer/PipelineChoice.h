#pragma once
// The rendering pipelines the viewer's combo offers, and how each one is
// set in RenderSettings. Only the ray traced pipeline exists on this branch;
// once RenderSettings has a pipeline field, adding the hybrid pipeline is
// one more line here, e.g.
//   PipelineChoice{"hybrid", [](RenderSettings& s) { s.pipeline = Pipeline::Hybrid; }},
#include <array>

#include "render/RenderSettings.h"

namespace raycache {

struct PipelineChoice {
    const char* label;
    void (*apply)(RenderSettings&);
};

inline constexpr std::array kPipelineChoices = {
    PipelineChoice{"ray", [](RenderSettings&) {}},  // primary rays traced: the only pipeline so far
};

}  // namespace raycache
