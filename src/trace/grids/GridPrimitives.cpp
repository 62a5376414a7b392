#include "trace/grids/GridPrimitives.h"

#include <algorithm>
#include <variant>

#include "trace/SphereIntersection.h"

namespace raycache {

void GridPrimitives::rebuild(const Scene& scene, const Parallel& parallel) {
    objects_.clear();
    firstPrimitive_.clear();
    count_ = 0;
    objects_.reserve(scene.objects.size());
    firstPrimitive_.reserve(scene.objects.size() + 1);
    for (const SceneObject& object : scene.objects) {
        firstPrimitive_.push_back(count_);
        ObjectGeometry geometry;
        if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
            geometry.sphere = sphere;
            count_ += 1;
        } else {
            geometry.mesh = std::get<MeshShape>(object.shape).mesh.get();
            count_ += static_cast<std::uint32_t>(geometry.mesh->triangles.size());
        }
        objects_.push_back(geometry);
    }
    firstPrimitive_.push_back(count_);
    primitiveObject_.resize(count_);
    corners_.resize(count_);
    isSphere_.resize(count_);
    // Blocks of primitives, each filled from its objects' geometry.
    constexpr std::uint32_t kBlock = 16384;
    const int blocks = static_cast<int>((count_ + kBlock - 1) / kBlock);
    parallel.forEachIndex(blocks, [&](int b, int) {
        const std::uint32_t begin = static_cast<std::uint32_t>(b) * kBlock;
        const std::uint32_t end = std::min(count_, begin + kBlock);
        // The object holding `begin`: the last whose first primitive is at or before it.
        std::size_t o = static_cast<std::size_t>(
            std::upper_bound(firstPrimitive_.begin(), firstPrimitive_.end() - 1, begin) - firstPrimitive_.begin() - 1);
        for (std::uint32_t p = begin; p < end; ++p) {
            while (p >= firstPrimitive_[o + 1]) ++o;
            primitiveObject_[p] = static_cast<int>(o);
            const ObjectGeometry& geometry = objects_[o];
            isSphere_[p] = geometry.sphere ? 1 : 0;
            if (geometry.sphere) continue;
            const auto& indices = geometry.mesh->triangles[p - firstPrimitive_[o]];
            const Vec3& p0 = geometry.mesh->positions[indices[0]];
            const Vec3& p1 = geometry.mesh->positions[indices[1]];
            const Vec3& p2 = geometry.mesh->positions[indices[2]];
            corners_[p] = {p0.x, p0.y, p0.z, p1.x, p1.y, p1.z, p2.x, p2.y, p2.z};
        }
    });
}

void GridPrimitives::intersect(std::uint32_t primitive, const Ray& ray, const WatertightRay& watertight,
                               TraceHit& best) const {
    const int object = objectOf(primitive);
    const ObjectGeometry& geometry = objects_[static_cast<std::size_t>(object)];
    const float tFar = best.hit() ? best.t : ray.tFar;
    if (geometry.sphere) {
        const float t = sphereRoot(*geometry.sphere, ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x,
                                   ray.direction.y, ray.direction.z, ray.tNear, tFar);
        if (t >= 0.0f && nearer(t, object, 0, best)) best = TraceHit{t, object, 0, 0.0f, 0.0f};
        return;
    }
    Vec3 p0, p1, p2;
    triangle(primitive, p0, p1, p2);
    WatertightRay bounded = watertight;
    bounded.tFar = tFar;
    TriangleHit hit;
    const int local = localIndex(primitive);
    if (intersectWatertight(bounded, p0, p1, p2, hit) && nearer(hit.t, object, local, best))
        best = TraceHit{hit.t, object, local, hit.u, hit.v};
}

bool GridPrimitives::occludes(std::uint32_t primitive, const Ray& ray, const WatertightRay& watertight) const {
    const ObjectGeometry& geometry = objects_[static_cast<std::size_t>(objectOf(primitive))];
    if (geometry.sphere)
        return sphereRoot(*geometry.sphere, ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x, ray.direction.y,
                          ray.direction.z, ray.tNear, ray.tFar) >= 0.0f;
    Vec3 p0, p1, p2;
    triangle(primitive, p0, p1, p2);
    TriangleHit hit;
    return intersectWatertight(watertight, p0, p1, p2, hit);
}

}  // namespace raycache
