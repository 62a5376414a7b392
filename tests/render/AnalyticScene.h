#pragma once
// Test helpers for renders checked against closed-form answers: double-precision
// vector arithmetic (independent of the renderer's float code), the pixel rays
// of one fixed camera, and small scenes in front of it.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "core/Parallel.h"
#include "core/Transform.h"
#include "render/FrameRenderer.h"
#include "scene/MeshGenerators.h"
#include "trace/TraceScene.h"

namespace raycache::analytic {

inline constexpr int kSize = 64;

struct DVec {
    double x, y, z;
};
inline DVec operator-(DVec a, DVec b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline DVec operator+(DVec a, DVec b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline DVec operator*(DVec a, double s) {
    return {a.x * s, a.y * s, a.z * s};
}
inline double dot(DVec a, DVec b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline double length(DVec a) {
    return std::sqrt(dot(a, a));
}
inline DVec unit(DVec a) {
    return a * (1.0 / length(a));
}

inline const DVec kEye{0, 0, 5};

// The camera every analytic scene uses: at (0,0,5) looking down -z, 40 degree
// vertical fov, square kSize image, rays through pixel centres, row 0 on top.
inline Camera analyticCamera() {
    return Camera{{0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40.0f};
}
inline DVec pixelDirection(int x, int y) {
    const double t = std::tan(20.0 * std::numbers::pi / 180.0);
    const double sx = (2.0 * (x + 0.5) / kSize - 1.0) * t;
    const double sy = (1.0 - 2.0 * (y + 0.5) / kSize) * t;
    return unit({sx, sy, -1.0});
}
// The pixel whose centre ray passes nearest to `p` (in front of the camera).
inline void pixelOf(DVec p, int& x, int& y) {
    const double t = std::tan(20.0 * std::numbers::pi / 180.0);
    const DVec d = p - kEye;
    const double sx = d.x / -d.z / t, sy = d.y / -d.z / t;
    x = static_cast<int>(std::floor((sx + 1.0) * 0.5 * kSize));
    y = static_cast<int>(std::floor((1.0 - sy) * 0.5 * kSize));
}

// The ray from `o` along unit `d` meets the sphere (c, r): discriminant and nearest/farthest t.
struct SphereHit {
    double disc, tNear, tFar;
};
inline SphereHit raySphere(DVec o, DVec d, DVec c, double r) {
    const DVec oc = o - c;
    const double b = dot(oc, d), disc = b * b - (dot(oc, oc) - r * r);
    const double s = disc >= 0 ? std::sqrt(disc) : 0.0;
    return {disc, -b - s, -b + s};
}

// A 20 x 20 wall in the plane z = 0 facing the camera (+z), with `material`.
inline SceneObject wallAtZeroFacingCamera(const Material& material) {
    // makePlane() lies in xz with normal +y; 90 degrees about x turns +y into +z.
    const Transform t = Transform::rotate({1, 0, 0}, 90.0f) * Transform::scale({20, 1, 20});
    return SceneObject{
        "wall", MeshShape{std::make_shared<const TriangleMesh>(transformed(makePlane(), t))}, material, {0, 0, 0}};
}

inline Image renderAnalytic(const Scene& scene) {
    RenderSettings settings;
    settings.width = settings.height = kSize;
    const TraceScene tracer(scene);
    const Parallel parallel(2);
    const FrameRenderer renderer(scene, tracer, settings, parallel);
    Image film;
    renderer.render(scene.camera, film);
    return film;
}

}  // namespace raycache::analytic
