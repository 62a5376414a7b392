#include "render/RenderSettings.h"

namespace raycache {

const char* pipelineKindName(PipelineKind kind) {
    switch (kind) {
        case PipelineKind::Ray: return "ray";
        case PipelineKind::Hybrid: return "hybrid";
        case PipelineKind::RenderCache: return "render-cache";
    }
    return "ray";
}

const char* gbufferSourceName(GBufferSource source) {
    switch (source) {
        case GBufferSource::Auto: return "auto";
        case GBufferSource::OpenGl: return "gl";
        case GBufferSource::Packets: return "packets";
    }
    return "auto";
}

std::optional<PipelineKind> parsePipelineKind(const std::string& name) {
    for (const PipelineKind kind : kPipelineKinds)
        if (name == pipelineKindName(kind)) return kind;
    return std::nullopt;
}

}  // namespace raycache
