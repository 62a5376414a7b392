#pragma once
// How a frame is made: primary rays per tile (Ray); a G-buffer followed by
// deferred shadow and secondary passes (Hybrid, as in Ruff's thesis); or reprojected
// samples of earlier frames plus a budget of new rays (RenderCache, after Walter et al. 1999).
// The pipelines themselves live in render/ and rendercache/; their names are
// here, below them, because the scene format names them too ("pipeline"):
// the scene file, the command line and the reports read them from here.
#include <array>

namespace raycache {

enum class PipelineKind { Ray, Hybrid, RenderCache };
// Every pipeline, in the order messages and help texts list them.
inline constexpr std::array kPipelineKinds{PipelineKind::Ray, PipelineKind::Hybrid, PipelineKind::RenderCache};

// "ray", "hybrid", "render-cache".
constexpr const char* pipelineKindName(PipelineKind kind) {
    switch (kind) {
        case PipelineKind::Ray: return "ray";
        case PipelineKind::Hybrid: return "hybrid";
        case PipelineKind::RenderCache: return "render-cache";
    }
    return "ray";
}

}  // namespace raycache
