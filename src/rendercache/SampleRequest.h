#pragma once
// What one display frame of the asynchronous Render Cache
// (rendercache/AsyncRenderCache.h) asks its tracer for: the pixels its
// request map chose, through the camera it was made for, and the pixels
// where the predicted next camera will find holes, through that camera.
#include <vector>

#include "render/CameraRays.h"
#include "scene/Camera.h"

namespace raycache {

struct SampleRequest {
    Camera camera;
    std::vector<PixelCoord> pixels;
    Camera nextCamera;                  // the extrapolated camera of the next frame
    std::vector<PixelCoord> predicted;  // through nextCamera; empty when the frame does not predict
    bool refreshesAll = false;          // every pixel (first frame, or a cut)

    std::size_t size() const { return pixels.size() + predicted.size(); }
};

}  // namespace raycache
