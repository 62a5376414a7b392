#pragma once
// Samples the asynchronous Render Cache's tracer traced
// (rendercache/AsyncRenderCache.h), waiting to be merged into the sample
// pool by the next display frame: the ray through pixels[i] of `camera`
// found samples[i].
#include <vector>

#include "render/CameraRays.h"
#include "render/TileKernel.h"
#include "scene/Camera.h"

namespace raycache {

struct SampleBatch {
    Camera camera;
    std::vector<PixelCoord> pixels;
    std::vector<PrimarySample> samples;
    bool endsRequest = false;  // the last batch of its SampleRequest
};

}  // namespace raycache
