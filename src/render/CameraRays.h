#pragma once
// Primary rays of a pinhole camera through pixel centres, or through one
// sample of each pixel's jittered set (render/PixelSamples.h, `--spp`).
#include "core/Ray.h"
#include "render/PixelSamples.h"
#include "trace/RayPacket.h"
#include "scene/Camera.h"

namespace raycache {

// A pixel of the image, x to the right, y down from the top row.
struct PixelCoord {
    int x = 0, y = 0;
    bool operator==(const PixelCoord&) const = default;
};

class CameraRays {
public:
    CameraRays(const Camera& camera, int width, int height);
    // The rays of sample `sample` of every pixel instead of the centres;
    // `samples` must outlive this object.
    CameraRays(const Camera& camera, int width, int height, const PixelSamples& samples, int sample);

    // Ray through the centre of pixel (x, y) (or its sample); y = 0 is the top row.
    Ray ray(int x, int y) const {
        const PixelOffset o = samples_ ? samples_->offset(x, y, sample_) : PixelOffset{};
        const float sx = (2.0f * (static_cast<float>(x) + o.x) * invWidth_ - 1.0f);
        const float sy = (1.0f - 2.0f * (static_cast<float>(y) + o.y) * invHeight_);
        return Ray{origin_, normalize(forward_ + right_ * sx + up_ * sy)};
    }

    // out[k] = ray(x0 + k, y) for k < count (count <= 16), sixteen at a
    // time (core/FloatLanes.h): the same bits as ray().
    void rowOfRays(int x0, int y, int count, Ray* out) const;
    // The same sixteen rays (x0 + k for every k < 16, also past the row's
    // end) written into a packet for the tracer, tNear 0 and tFar infinite.
    void rowOfRays(int x0, int y, RayLanes16& out) const;

    // The angle between the rays of neighbouring pixels at the image's
    // centre (radians): where a pixel's cone starts (render/RayCone.h).
    float pixelSpread() const { return 2.0f * pixelSpread_ * invHeight_; }

private:
    const PixelSamples* samples_ = nullptr;  // null: pixel centres
    int sample_ = 0;
    float pixelSpread_ = 0.0f;  // tan(fov / 2)
    Vec3 origin_, forward_, right_, up_;  // right_/up_ scaled to the image plane at distance 1
    float invWidth_, invHeight_;
};

}  // namespace raycache
