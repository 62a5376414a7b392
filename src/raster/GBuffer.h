#pragma once
// The G-buffer of the hybrid pipeline (Ruff's MSc thesis, 2013): what the primary visibility
// pass leaves for the deferred passes, per pixel. OpenGL writes it in exactly
// this layout and the deferred passes read it in place (from the mapped
// readback buffer), so the packet-based fallback fills the same layout.
//
// Row-major, row 0 at the top (as Image). Per pixel:
//   positionDepth  4 floats: world position xyz, w = distance along the
//                  pixel's camera ray (negative: no surface, background)
//   normal         4 floats: unit shading normal xyz on the object's outside
//                  (not yet turned toward the viewer), w unused
//   albedo         4 floats: diffuse albedo rgb (linear), a unused
//   ids            2 ints:   object id (index in Scene::objects, -1: none),
//                  primitive id (triangle index in a mesh, 0 for spheres)
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Rgb.h"
#include "core/Vec3.h"

namespace raycache {

// Read-only view of a G-buffer held elsewhere (GL's mapped buffer or a GBufferStorage).
struct GBufferView {
    int width = 0;
    int height = 0;
    const float* positionDepth = nullptr;
    const float* normal = nullptr;
    const float* albedo = nullptr;
    const std::int32_t* ids = nullptr;

    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }
    bool hasSurface(std::size_t i) const { return ids[2 * i] >= 0; }
    int objectId(std::size_t i) const { return ids[2 * i]; }
    int primitiveId(std::size_t i) const { return ids[2 * i + 1]; }
    Vec3 position(std::size_t i) const {
        return {positionDepth[4 * i], positionDepth[4 * i + 1], positionDepth[4 * i + 2]};
    }
    Vec3 normalAt(std::size_t i) const { return {normal[4 * i], normal[4 * i + 1], normal[4 * i + 2]}; }
    Rgb albedoAt(std::size_t i) const { return {albedo[4 * i], albedo[4 * i + 1], albedo[4 * i + 2]}; }
};

// A G-buffer in ordinary memory, for the CPU producer.
struct GBufferStorage {
    int width = 0;
    int height = 0;
    std::vector<float> positionDepth, normal, albedo;
    std::vector<std::int32_t> ids;

    void resize(int w, int h) {
        width = w;
        height = h;
        const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
        positionDepth.resize(4 * n);
        normal.resize(4 * n);
        albedo.resize(4 * n);
        ids.resize(2 * n);
    }
    GBufferView view() const {
        return {width, height, positionDepth.data(), normal.data(), albedo.data(), ids.data()};
    }
};

}  // namespace raycache
