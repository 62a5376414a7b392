#include "scene/VertexNormals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace raycache {
namespace {

constexpr std::uint32_t kNoTriangle = UINT32_MAX;

// The unit normal of triangle `t`, in double precision: the fallback for a
// vertex whose float sum vanished or overflowed, where the float cross
// product may have overflowed too. +y if the triangle has no area after all.
Vec3 unitNormalOf(const TriangleMesh& mesh, std::uint32_t t) {
    const auto& tri = mesh.triangles[t];
    const Vec3 &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
    const double ux = double(b.x) - a.x, uy = double(b.y) - a.y, uz = double(b.z) - a.z;
    const double vx = double(c.x) - a.x, vy = double(c.y) - a.y, vz = double(c.z) - a.z;
    const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    const double l = std::sqrt(nx * nx + ny * ny + nz * nz);
    if (!(l > 0.0) || !std::isfinite(l)) return {0.0f, 1.0f, 0.0f};
    return {static_cast<float>(nx / l), static_cast<float>(ny / l), static_cast<float>(nz / l)};
}

// Sums the triangles' cross products into the slot `slotOf[v]` of each
// corner v, then gives every vertex its slot's normalized sum. The float
// arithmetic (sum in triangle order, n * (1 / |n|)) is what deforming
// meshes have always used, so their images do not change.
std::vector<Vec3> normalsBySlot(const TriangleMesh& mesh, const std::vector<std::uint32_t>& slotOf) {
    const std::size_t n = mesh.positions.size();
    std::vector<Vec3> sum(n, Vec3{0.0f, 0.0f, 0.0f});
    // Each slot's largest triangle, for the fallback.
    std::vector<std::uint32_t> largest(n, kNoTriangle);
    std::vector<float> largestArea2(n, 0.0f);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const Vec3 c =
            cross(mesh.positions[tri[1]] - mesh.positions[tri[0]], mesh.positions[tri[2]] - mesh.positions[tri[0]]);
        const float area2 = dot(c, c);
        for (std::uint32_t v : tri) {
            const std::uint32_t s = slotOf[v];
            sum[s] += c;
            if (area2 > largestArea2[s]) {
                largestArea2[s] = area2;
                largest[s] = static_cast<std::uint32_t>(t);
            }
        }
    }
    std::vector<Vec3> normals(n);
    for (std::size_t v = 0; v < n; ++v) {
        const std::uint32_t s = slotOf[v];
        const float l = length(sum[s]);
        if (l > 0.0f && std::isfinite(l))
            normals[v] = sum[s] * (1.0f / l);
        else
            normals[v] = largest[s] == kNoTriangle ? Vec3{0.0f, 1.0f, 0.0f} : unitNormalOf(mesh, largest[s]);
    }
    return normals;
}

}  // namespace

std::vector<Vec3> areaWeightedNormals(const TriangleMesh& mesh) {
    std::vector<std::uint32_t> own(mesh.positions.size());
    std::iota(own.begin(), own.end(), 0u);
    return normalsBySlot(mesh, own);
}

std::vector<Vec3> smoothNormalsByPosition(const TriangleMesh& mesh) {
    // Vertices sorted by position; each run of equal positions shares the
    // slot of its lowest index, so the result does not depend on the sort.
    const auto& p = mesh.positions;
    std::vector<std::uint32_t> order(p.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto less = [&](std::uint32_t a, std::uint32_t b) {
        if (p[a].x != p[b].x) return p[a].x < p[b].x;
        if (p[a].y != p[b].y) return p[a].y < p[b].y;
        if (p[a].z != p[b].z) return p[a].z < p[b].z;
        return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    std::vector<std::uint32_t> slotOf(p.size());
    for (std::size_t i = 0; i < order.size();) {
        std::size_t end = i + 1;
        while (end < order.size() && p[order[end]] == p[order[i]]) ++end;
        for (std::size_t k = i; k < end; ++k) slotOf[order[k]] = order[i];  // order[i] is the run's lowest index
        i = end;
    }
    return normalsBySlot(mesh, slotOf);
}

}  // namespace raycache
