#include "render/RenderSettings.h"

namespace raycache {

const char* gbufferSourceName(GBufferSource source) {
    switch (source) {
        case GBufferSource::Auto: return "auto";
        case GBufferSource::OpenGl: return "gl";
        case GBufferSource::Packets: return "packets";
    }
    return "auto";
}

}  // namespace raycache
