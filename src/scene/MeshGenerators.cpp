#include "scene/MeshGenerators.h"

#include <cmath>
#include <numbers>

namespace raycache {

namespace {
constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

struct MeshBuilder {
    TriangleMesh mesh;
    std::uint32_t vertex(const Vec3& p, const Vec3& n, float u, float v) {
        mesh.positions.push_back(p);
        mesh.normals.push_back(normalize(n));
        mesh.uvs.push_back({u, v});
        return static_cast<std::uint32_t>(mesh.positions.size() - 1);
    }
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) { mesh.triangles.push_back({a, b, c}); }
    void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
        triangle(a, b, c);
        triangle(a, c, d);
    }
    // Flat disc at height y facing `up` (+1 or -1).
    void cap(float y, float radius, int segments, float up) {
        const std::uint32_t centre = vertex({0, y, 0}, {0, up, 0}, 0.5f, 0.5f);
        std::uint32_t first = 0, previous = 0;
        for (int i = 0; i <= segments; ++i) {
            const float a = kTwoPi * static_cast<float>(i % segments) / static_cast<float>(segments);
            const float c = std::cos(a), s = std::sin(a);
            const std::uint32_t v = vertex({radius * c, y, radius * s}, {0, up, 0}, 0.5f + 0.5f * c, 0.5f + 0.5f * s);
            if (i == 0) first = v;
            else if (up > 0) triangle(centre, v, previous);
            else triangle(centre, previous, v);
            previous = v;
        }
        (void)first;
    }
};

Vec3 ring(float angle, float radius, float y) { return {radius * std::cos(angle), y, radius * std::sin(angle)}; }
}  // namespace

TriangleMesh makePlane() {
    MeshBuilder b;
    const Vec3 n{0, 1, 0};
    b.quad(b.vertex({-0.5f, 0, -0.5f}, n, 0, 0), b.vertex({-0.5f, 0, 0.5f}, n, 0, 1),
           b.vertex({0.5f, 0, 0.5f}, n, 1, 1), b.vertex({0.5f, 0, -0.5f}, n, 1, 0));
    return std::move(b.mesh);
}

TriangleMesh makeBox() {
    MeshBuilder b;
    // One face per axis direction, four vertices each so normals stay flat.
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            Vec3 n{}, u{}, v{};
            const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
            auto set = [](Vec3& w, int i, float x) { (i == 0 ? w.x : (i == 1 ? w.y : w.z)) = x; };
            set(n, axis, sign);
            set(u, ua, 0.5f);
            set(v, va, 0.5f * sign);
            const Vec3 c = n * 0.5f;
            b.quad(b.vertex(c - u - v, n, 0, 0), b.vertex(c + u - v, n, 1, 0), b.vertex(c + u + v, n, 1, 1),
                   b.vertex(c - u + v, n, 0, 1));
        }
    }
    return std::move(b.mesh);
}

TriangleMesh makeCylinder(int segments) {
    MeshBuilder b;
    for (int i = 0; i < segments; ++i) {
        const float a0 = kTwoPi * static_cast<float>(i) / static_cast<float>(segments);
        const float a1 = kTwoPi * static_cast<float>(i + 1) / static_cast<float>(segments);
        const float u0 = static_cast<float>(i) / static_cast<float>(segments);
        const float u1 = static_cast<float>(i + 1) / static_cast<float>(segments);
        const Vec3 n0 = ring(a0, 1, 0), n1 = ring(a1, 1, 0);
        b.quad(b.vertex(ring(a0, 0.5f, -0.5f), n0, u0, 0), b.vertex(ring(a0, 0.5f, 0.5f), n0, u0, 1),
               b.vertex(ring(a1, 0.5f, 0.5f), n1, u1, 1), b.vertex(ring(a1, 0.5f, -0.5f), n1, u1, 0));
    }
    b.cap(0.5f, 0.5f, segments, 1.0f);
    b.cap(-0.5f, 0.5f, segments, -1.0f);
    return std::move(b.mesh);
}

TriangleMesh makeCone(int segments) {
    MeshBuilder b;
    // Side normal of a cone with radius 0.5 and height 1: (cos a, 0.5, sin a) normalized.
    for (int i = 0; i < segments; ++i) {
        const float a0 = kTwoPi * static_cast<float>(i) / static_cast<float>(segments);
        const float a1 = kTwoPi * static_cast<float>(i + 1) / static_cast<float>(segments);
        const float am = 0.5f * (a0 + a1);
        const float u0 = static_cast<float>(i) / static_cast<float>(segments);
        const float u1 = static_cast<float>(i + 1) / static_cast<float>(segments);
        const Vec3 apexNormal{std::cos(am), 0.5f, std::sin(am)};
        b.triangle(b.vertex(ring(a0, 0.5f, -0.5f), {std::cos(a0), 0.5f, std::sin(a0)}, u0, 0),
                   b.vertex({0, 0.5f, 0}, apexNormal, 0.5f * (u0 + u1), 1),
                   b.vertex(ring(a1, 0.5f, -0.5f), {std::cos(a1), 0.5f, std::sin(a1)}, u1, 0));
    }
    b.cap(-0.5f, 0.5f, segments, -1.0f);
    return std::move(b.mesh);
}

TriangleMesh makeTorus(float major, float minor, int ringSegments, int tubeSegments) {
    MeshBuilder b;
    for (int i = 0; i <= ringSegments; ++i) {
        const float a = kTwoPi * static_cast<float>(i) / static_cast<float>(ringSegments);
        for (int j = 0; j <= tubeSegments; ++j) {
            const float t = kTwoPi * static_cast<float>(j) / static_cast<float>(tubeSegments);
            const Vec3 dir{std::cos(a), 0, std::sin(a)};
            const Vec3 n = dir * std::cos(t) + Vec3{0, std::sin(t), 0};
            b.vertex(dir * major + n * minor, n, static_cast<float>(i) / static_cast<float>(ringSegments),
                     static_cast<float>(j) / static_cast<float>(tubeSegments));
        }
    }
    const auto stride = static_cast<std::uint32_t>(tubeSegments + 1);
    for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(ringSegments); ++i)
        for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(tubeSegments); ++j) {
            const std::uint32_t a = i * stride + j, c = (i + 1) * stride + j;
            b.quad(a, a + 1, c + 1, c);
        }
    return std::move(b.mesh);
}

TriangleMesh makeBowl(float wallThickness, int segments) {
    MeshBuilder b;
    const int rings = segments / 4;
    const float outer = 0.5f, inner = 0.5f - wallThickness;
    // Lower hemisphere shells: outer faces out, inner faces toward the centre.
    const auto shell = [&](float radius, bool outward) {
        const auto base = static_cast<std::uint32_t>(b.mesh.positions.size());
        for (int r = 0; r <= rings; ++r) {
            const float polar = 0.5f * std::numbers::pi_v<float> * static_cast<float>(r) / static_cast<float>(rings);
            for (int s = 0; s <= segments; ++s) {
                const float a = kTwoPi * static_cast<float>(s) / static_cast<float>(segments);
                const Vec3 d{std::sin(polar) * std::cos(a), -std::cos(polar), std::sin(polar) * std::sin(a)};
                b.vertex(d * radius, outward ? d : -d, static_cast<float>(s) / static_cast<float>(segments),
                         static_cast<float>(r) / static_cast<float>(rings));
            }
        }
        const auto stride = static_cast<std::uint32_t>(segments + 1);
        for (std::uint32_t r = 0; r < static_cast<std::uint32_t>(rings); ++r)
            for (std::uint32_t s = 0; s < static_cast<std::uint32_t>(segments); ++s) {
                const std::uint32_t a = base + r * stride + s, c = a + stride;
                if (outward) b.quad(a, a + 1, c + 1, c);
                else b.quad(a, c, c + 1, a + 1);
            }
    };
    shell(outer, true);
    shell(inner, false);
    // Rim joining the two shells at y = 0.
    for (int s = 0; s < segments; ++s) {
        const float a0 = kTwoPi * static_cast<float>(s) / static_cast<float>(segments);
        const float a1 = kTwoPi * static_cast<float>(s + 1) / static_cast<float>(segments);
        const Vec3 up{0, 1, 0};
        b.quad(b.vertex(ring(a0, inner, 0), up, 0, 0), b.vertex(ring(a1, inner, 0), up, 1, 0),
               b.vertex(ring(a1, outer, 0), up, 1, 1), b.vertex(ring(a0, outer, 0), up, 0, 1));
    }
    return std::move(b.mesh);
}

}  // namespace raycache
