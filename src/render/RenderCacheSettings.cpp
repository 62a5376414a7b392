#include "render/RenderCacheSettings.h"

#include <cmath>
#include <sstream>
#include <string>

#include "core/Errors.h"
#include "core/TextFormat.h"

namespace raycache {

namespace {

bool within(float v, float lo, float hi) { return std::isfinite(v) && v >= lo && v <= hi; }

}  // namespace

void validateRenderCacheSettings(const RenderCacheSettings& s) {
    if (!within(s.alpha, 0.0f, 1.0f)) throw InputError("--rc-alpha must be in [0, 1] (got " + formatGeneral(s.alpha) + ")");
    if (!(std::isfinite(s.budget) && s.budget > 0.0f && s.budget <= 1.0f))
        throw InputError("--rc-budget must be a share of the pixels in (0, 1] (got " + formatGeneral(s.budget) + ")");
    if (!within(s.targetFrameMs, 0.0f, 60000.0f))
        throw InputError("--rc-target-ms must be between 0 (off) and 60000 (got " + formatGeneral(s.targetFrameMs) + ")");
    if (s.reshadeInterval < 1 || s.reshadeInterval > kMaxReshadeInterval)
        throw InputError("--rc-reshade-every must be between 1 and " + std::to_string(kMaxReshadeInterval) +
                         " frames (got " + std::to_string(s.reshadeInterval) + ")");
    if (s.maxAge < 1 || s.maxAge > 65000)
        throw InputError("--rc-max-age must be between 1 and 65000 frames (got " + std::to_string(s.maxAge) + ")");
    if (!within(s.predictShare, 0.0f, 0.9f))
        throw InputError("--rc-predict must be in [0, 0.9] (got " + formatGeneral(s.predictShare) + ")");
    if (!within(s.margin, 0.0f, 0.5f))
        throw InputError("--rc-margin must be in [0, 0.5] (got " + formatGeneral(s.margin) + ")");
    if (!within(s.depthCullThreshold, 0.0f, 1.0f))
        throw InputError("--rc-depth-cull must be in [0, 1] (got " + formatGeneral(s.depthCullThreshold) + ")");
    if (s.requestTileSize < 1 || s.requestTileSize > 256)
        throw InputError("--rc-tile must be between 1 and 256 pixels (got " + std::to_string(s.requestTileSize) + ")");
    if (!within(s.refreshAllHoleShare, 0.0f, 1.0f))
        throw InputError("render cache refresh-all hole share must be in [0, 1]");
}

const char* textureRefetchName(bool textureRefetch) { return textureRefetch ? "refetch" : "reproject"; }

}  // namespace raycache
