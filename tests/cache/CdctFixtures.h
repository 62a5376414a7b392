#pragma once
// What the CDCT tests (parity and improved) share: a one-mirror scene, colors
// that tell texels apart, rays that are awkward for a relief search, and a
// bit-exact image comparison.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "ImageCompare.h"
#include "core/Image.h"
#include "scene/Scene.h"

namespace raycache::cdct_test {

// The depth a CDCT texel holds for a ray that met nothing.
inline constexpr float kInf = std::numeric_limits<float>::infinity();

// One mirror sphere of radius 1 at the origin, cached with `technique`.
inline Scene oneMirror(CacheTechnique technique, int resolution) {
    Scene s;
    Material mirror;
    mirror.reflectivity = 0.8f;
    mirror.cache.technique = technique;
    mirror.cache.faceResolution = resolution;
    s.objects.push_back(SceneObject{"m", Sphere{{0, 0, 0}, 1}, mirror, {0, 0, 0}});
    return s;
}

// The same mirror cached with CCT.
inline Scene oneCctMirror(int resolution) { return oneMirror(CacheTechnique::Cct, resolution); }

// A uniformly random unit direction.
inline Vec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<float> g;
    for (;;) {
        const Vec3 d{g(rng), g(rng), g(rng)};
        if (dot(d, d) > 1e-6f) return normalize(d);
    }
}

// A color telling texels apart.
inline Rgb colorOf(int texel) {
    return Rgb{static_cast<float>(texel % 97) + 1.0f, static_cast<float>(texel / 97) + 1.0f, 0.5f};
}

struct Probe {
    Vec3 origin, direction;
};

// Rays that start on (just off) the unit sphere and graze the box, run
// parallel to its faces, leave through edges and corners, run tangent to
// the sphere or start outside or inside it.
inline std::vector<Probe> awkwardRays() {
    const float s = 1.0f / std::sqrt(3.0f);
    return {
        {{0, 1.0001f, 0}, {1, 0, 0}},                    // parallel to the +y face, on the sphere's top
        {{0, 1.0001f, 0}, {0, 0, -1}},                   // parallel to the +y face, other axis
        {{1.0001f, 0, 0}, {0, 1, 0}},                    // tangent, along the +x face
        {{0, 0, 1.0001f}, {0, 0, 1}},                    // straight out through a face centre (radial)
        {{s, s, s}, {s, s, s}},                          // out through the box corner
        {{0.7071f, 0.7071f, 0}, {0.7071f, 0.7071f, 0}},  // out through an edge
        {{0, -1.0001f, 0}, {1e-7f, 1, 1e-7f}},           // nearly parallel to the x/z faces, pointing back through
        {{1.5f, 0, 0}, {1, 0, 0}},                       // origin outside the box, moving away
        {{0.3f, 0.2f, 0.1f}, {0.0f, -1.0f, 0.0f}},       // origin inside the object
        {{0.6f, 0.8f, 0.0f}, {0.8f, -0.6f, 0.0f}},       // tangent to the sphere
    };
}

}  // namespace raycache::cdct_test
