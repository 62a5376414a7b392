#include "render/CameraRays.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/FloatLanes.h"
#include "core/LaneLevels.h"
#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

namespace {

struct CameraFrame {
    Vec3 origin, forward, right, up;
    float invWidth, invHeight;
};

}  // namespace

#define RAYCACHE_LANE_KERNELS "render/CameraRayKernels.inc"
#include "core/LaneLevelsInclude.h"

CameraRays::CameraRays(const Camera& camera, int width, int height, const PixelSamples& samples, int sample)
    : CameraRays(camera, width, height) {
    samples_ = &samples;
    sample_ = sample;
}

CameraRays::CameraRays(const Camera& camera, int width, int height)
    : origin_(camera.position),
      invWidth_(1.0f / static_cast<float>(width)),
      invHeight_(1.0f / static_cast<float>(height)) {
    const float tanHalf = std::tan(0.5f * camera.verticalFovDeg * std::numbers::pi_v<float> / 180.0f);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    forward_ = normalize(camera.lookAt - camera.position);
    const Vec3 right = normalize(cross(forward_, camera.up));
    const Vec3 up = cross(right, forward_);
    right_ = right * (tanHalf * aspect);
    up_ = up * tanHalf;
    pixelSpread_ = tanHalf;
}

void CameraRays::rowOfRays(int x0, int y, int count, Ray* out) const {
    if (samples_) {
        for (int k = 0; k < count; ++k) out[k] = ray(x0 + k, y);
        return;
    }
    RAYCACHE_LANE_DISPATCH(rowLanes, CameraFrame{origin_, forward_, right_, up_, invWidth_, invHeight_}, x0, y, count,
                           out);
}

void CameraRays::rowOfRays(int x0, int y, RayLanes16& out) const {
    RAYCACHE_LANE_DISPATCH(rowLanes, CameraFrame{origin_, forward_, right_, up_, invWidth_, invHeight_}, x0, y, out,
                           samples_, sample_);
}

}  // namespace raycache
