#pragma once
// The progress line every rendering command prints after each frame, so
// `render` and `cache-view` report frames identically.
#include <string>

#include "core/TextFormat.h"
#include "session/FrameLoop.h"

namespace raycache {

// "frame 3/48  26.6 ms  rays: primary ..., ...  21.54 Mrays/s[  cache: ...][  phases ms: ...]",
// without a newline; the cache part appears when the frame used caches, the
// phases (raster, readback, shadows, secondary, compose) for the hybrid pipeline.
std::string formatFrameLine(const FrameResult& result, int frameCount);

}  // namespace raycache
