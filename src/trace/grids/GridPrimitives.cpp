#include "trace/grids/GridPrimitives.h"

#include <variant>

#include "trace/SphereIntersection.h"

namespace raycache {

GridPrimitives::GridPrimitives(const Scene& scene) {
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
    for (std::size_t o = 0; o < objects_.size(); ++o)
        for (std::uint32_t p = firstPrimitive_[o]; p < firstPrimitive_[o + 1]; ++p)
            primitiveObject_[p] = static_cast<int>(o);
}

const Sphere* GridPrimitives::sphere(std::uint32_t primitive) const {
    return objects_[static_cast<std::size_t>(objectOf(primitive))].sphere;
}

void GridPrimitives::triangle(std::uint32_t primitive, Vec3& p0, Vec3& p1, Vec3& p2) const {
    const int object = objectOf(primitive);
    const TriangleMesh& mesh = *objects_[static_cast<std::size_t>(object)].mesh;
    const auto& indices = mesh.triangles[primitive - firstPrimitive_[static_cast<std::size_t>(object)]];
    p0 = mesh.positions[indices[0]];
    p1 = mesh.positions[indices[1]];
    p2 = mesh.positions[indices[2]];
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
        return sphereRoot(*geometry.sphere, ray.origin.x, ray.origin.y, ray.origin.z, ray.direction.x,
                          ray.direction.y, ray.direction.z, ray.tNear, ray.tFar) >= 0.0f;
    Vec3 p0, p1, p2;
    triangle(primitive, p0, p1, p2);
    TriangleHit hit;
    return intersectWatertight(watertight, p0, p1, p2, hit);
}

}  // namespace raycache
