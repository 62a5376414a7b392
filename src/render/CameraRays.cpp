#include "render/CameraRays.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/FloatLanes.h"
#include "core/LaneClones.h"

namespace raycache {

namespace {

struct CameraFrame {
    Vec3 origin, forward, right, up;
    float invWidth, invHeight;
};

// The directions of the rays through sixteen pixels of row y from column
// x0, each at its offsets in its pixel (½, ½: the centre).
[[gnu::always_inline]] inline void jitteredRowDirections(const CameraFrame& c, int x0, int y, const FloatLanes& offsetX,
                                                        const FloatLanes& offsetY, FloatLanes& nx, FloatLanes& ny,
                                                        FloatLanes& nz) {
    const IntLanes16 column = IntLanes16{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15} + x0;
    const FloatLanes x = __builtin_convertvector(column, FloatLanes);
    const FloatLanes sx = 2.0f * (x + offsetX) * c.invWidth - 1.0f;
    const FloatLanes sy = 1.0f - 2.0f * (static_cast<float>(y) + offsetY) * c.invHeight;
    // normalize(forward + right * sx + up * sy), in Vec3's order of operations.
    const FloatLanes dx = c.forward.x + c.right.x * sx + c.up.x * sy;
    const FloatLanes dy = c.forward.y + c.right.y * sx + c.up.y * sy;
    const FloatLanes dz = c.forward.z + c.right.z * sx + c.up.z * sy;
    FloatLanes length;
    sqrtLanes(dx * dx + dy * dy + dz * dz, length);
    const FloatLanes inverse = 1.0f / length;
    nx = dx * inverse, ny = dy * inverse, nz = dz * inverse;
}

// The rays through the pixels' centres.
[[gnu::always_inline]] inline void rowDirections(const CameraFrame& c, int x0, int y, FloatLanes& nx, FloatLanes& ny,
                                                FloatLanes& nz) {
    const FloatLanes half = FloatLanes{} + 0.5f;
    jitteredRowDirections(c, x0, y, half, half, nx, ny, nz);
}

// GCC resolves a function's clones in the file that defines them: the
// rowOfRays overloads call these.
RAYCACHE_WIDE_LANE_CLONES
void rowLanes(const CameraFrame& c, int x0, int y, int count, Ray* out) {
    FloatLanes nx, ny, nz;
    rowDirections(c, x0, y, nx, ny, nz);
    for (int k = 0; k < count; ++k) out[k] = Ray{c.origin, {nx[k], ny[k], nz[k]}};
}

RAYCACHE_WIDE_LANE_CLONES
void rowLanes(const CameraFrame& c, int x0, int y, RayLanes16& out, const PixelSamples* samples, int sample) {
    FloatLanes nx, ny, nz;
    if (samples) {
        FloatLanes offsetX, offsetY;
        for (int k = 0; k < kFloatLanes; ++k) {
            const PixelOffset o = samples->offset(x0 + k, y, sample);
            offsetX[k] = o.x;
            offsetY[k] = o.y;
        }
        jitteredRowDirections(c, x0, y, offsetX, offsetY, nx, ny, nz);
    } else {
        rowDirections(c, x0, y, nx, ny, nz);
    }
    storeLanes(nx, out.directionX);
    storeLanes(ny, out.directionY);
    storeLanes(nz, out.directionZ);
    storeLanes(FloatLanes{} + c.origin.x, out.originX);
    storeLanes(FloatLanes{} + c.origin.y, out.originY);
    storeLanes(FloatLanes{} + c.origin.z, out.originZ);
    storeLanes(FloatLanes{}, out.tNear);
    storeLanes(FloatLanes{}, out.time);
    storeLanes(FloatLanes{} + std::numeric_limits<float>::infinity(), out.tFar);
    for (int k = 0; k < kFloatLanes; ++k) {
        out.mask[k] = 0xFFFFFFFFu;
        out.id[k] = 0;
        out.flags[k] = 0;
    }
}

}  // namespace

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
    rowLanes({origin_, forward_, right_, up_, invWidth_, invHeight_}, x0, y, count, out);
}

void CameraRays::rowOfRays(int x0, int y, RayLanes16& out) const {
    rowLanes({origin_, forward_, right_, up_, invWidth_, invHeight_}, x0, y, out, samples_, sample_);
}

}  // namespace raycache
