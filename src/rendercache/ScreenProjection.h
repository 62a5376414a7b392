#pragma once
// The inverse of CameraRays: where a point lands on the image of a pinhole
// camera (v' = P'M'v, Zhu, Wang and Luebke 2005), in continuous pixel coordinates whose pixel
// (x, y) covers [x, x+1) x [y, y+1), and its depth along the view axis.
#include "core/Vec3.h"
#include "scene/Camera.h"

namespace raycache {

class ScreenProjection {
public:
    ScreenProjection(const Camera& camera, int width, int height);

    struct Projected {
        float x, y;   // continuous pixel coordinates, y down
        float depth;  // along the view axis; <= 0 behind the eye
    };
    // A point in world space.
    Projected point(const Vec3& world) const { return direction(world - eye_); }
    // A direction from the eye (a point infinitely far away that way).
    Projected direction(const Vec3& d) const {
        const float depth = dot(d, forward_);
        const float inv = 1.0f / depth;
        return {(dot(d, right_) * inv + 1.0f) * halfWidth_, (1.0f - dot(d, up_) * inv) * halfHeight_, depth};
    }
    const Vec3& eye() const { return eye_; }
    // What direction() computes from, for lane code that projects many
    // points with the same operations (rendercache/ProjectionLanes.h).
    const Vec3& forward() const { return forward_; }
    const Vec3& right() const { return right_; }
    const Vec3& up() const { return up_; }
    float halfWidth() const { return halfWidth_; }
    float halfHeight() const { return halfHeight_; }
    // Continuous coordinates are used only within (-kRange, kRange): beyond,
    // their conversion to int would overflow.
    static constexpr float kRange = 1.0e8f;
    // The pixel column or row a continuous coordinate lies in: its floor,
    // for |v| < 2^31. (std::floor without SSE4.1 is a sequence of masks and
    // subtractions, a visible share of a Render Cache frame.)
    static int pixelOf(float v) {
        const int truncated = static_cast<int>(v);
        return truncated - (static_cast<float>(truncated) > v ? 1 : 0);
    }

private:
    Vec3 eye_, forward_;
    Vec3 right_, up_;  // unit axes divided by the image plane's half extent at distance 1
    float halfWidth_, halfHeight_;
};

}  // namespace raycache
