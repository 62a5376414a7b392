#include "scene/ClothDrape.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace raycache {

namespace {

// The sheet lies this far off the surfaces it rests on, so shading points on
// it do not shadow themselves against the sphere or the floor.
constexpr float kClearance = 0.02f;

}  // namespace

ClothDrape::ClothDrape(const ClothDrapeShape& shape) : shape_(shape) {}

std::size_t ClothDrape::vertexCount() const {
    const auto n = static_cast<std::size_t>(shape_.cells) + 1;
    return n * n;
}

TriangleMesh ClothDrape::restMesh() const {
    TriangleMesh mesh;
    const int n = shape_.cells + 1;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float u = static_cast<float>(i) / static_cast<float>(shape_.cells);
            const float v = static_cast<float>(j) / static_cast<float>(shape_.cells);
            mesh.positions.push_back({shape_.sphereCenter.x + (2.0f * u - 1.0f) * shape_.halfSize, shape_.height,
                                      shape_.sphereCenter.z + (2.0f * v - 1.0f) * shape_.halfSize});
            mesh.normals.push_back({0.0f, 1.0f, 0.0f});
            mesh.uvs.push_back({u, v});
        }
    for (int j = 0; j < shape_.cells; ++j)
        for (int i = 0; i < shape_.cells; ++i) {
            const auto a = static_cast<std::uint32_t>(j * n + i);
            const auto b = a + 1, c = a + static_cast<std::uint32_t>(n), d = c + 1;
            // Counter-clockwise seen from above: normals point up.
            mesh.triangles.push_back({a, c, b});
            mesh.triangles.push_back({b, c, d});
        }
    return mesh;
}

Vec3 ClothDrape::drapedPoint(float x, float z) const {
    const Vec3& c = shape_.sphereCenter;
    const float r = shape_.sphereRadius + kClearance;
    const float d = std::sqrt(x * x + z * z);
    if (d == 0.0f) return c + Vec3{0.0f, r, 0.0f};
    const float dx = x / d, dz = z / d;
    const float arc = r * 0.5f * std::numbers::pi_v<float>;
    if (d <= arc) {
        const float phi = d / r;
        return c + Vec3{r * std::sin(phi) * dx, r * std::cos(phi), r * std::sin(phi) * dz};
    }
    const float drop = d - arc;
    const float fall = c.y - (shape_.floorY + kClearance);
    if (drop <= fall) return c + Vec3{r * dx, -drop, r * dz};
    const float out = r + (drop - fall);
    return {c.x + out * dx, shape_.floorY + kClearance, c.z + out * dz};
}

void ClothDrape::positionsAt(float time, std::span<Vec3> out) const {
    // Flat at t = 0, draped at half the period, flat again at its end.
    float phase = std::fmod(time / shape_.period, 1.0f);
    if (phase < 0.0f) phase += 1.0f;
    const float tri = 1.0f - std::fabs(2.0f * phase - 1.0f);
    const float s = tri * tri * (3.0f - 2.0f * tri);
    const int n = shape_.cells + 1;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x = (2.0f * static_cast<float>(i) / static_cast<float>(shape_.cells) - 1.0f) * shape_.halfSize;
            const float z = (2.0f * static_cast<float>(j) / static_cast<float>(shape_.cells) - 1.0f) * shape_.halfSize;
            const Vec3 flat = shape_.sphereCenter + Vec3{x, 0.0f, z};
            const Vec3 flatAtHeight{flat.x, shape_.height, flat.z};
            const Vec3 draped = drapedPoint(x, z);
            out[static_cast<std::size_t>(j * n + i)] = flatAtHeight * (1.0f - s) + draped * s;
        }
}

}  // namespace raycache
