#include "render/HitOnPrimitive.h"

#include <cmath>
#include <limits>

#include "trace/SphereIntersection.h"

namespace raycache {

namespace {

std::optional<TraceHit> hitOnSphere(const Sphere& sphere, int objectId, const Ray& ray, float expectedT) {
    const Vec3& o = ray.origin;
    const Vec3& d = ray.direction;
    // The root nearest expectedT: the first root past the midpoint between
    // the eye and the point, so that a sample on the far wall of a sphere the
    // eye is inside stays on that wall.
    const float t = sphereRoot(sphere, o.x, o.y, o.z, d.x, d.y, d.z, 0.5f * expectedT,
                               std::numeric_limits<float>::infinity());
    if (!(t > 0.0f)) return std::nullopt;
    return TraceHit{t, objectId, 0, 0.0f, 0.0f};
}

std::optional<TraceHit> hitOnTriangle(const TriangleOnItsPlane& triangle, int objectId, int primitiveId,
                                      const Ray& ray) {
    float t, u, v;
    if (!triangle.valid || !triangle.meet(ray, t, u, v)) return std::nullopt;
    return TraceHit{t, objectId, primitiveId, u, v};
}

}  // namespace

TriangleOnItsPlane::TriangleOnItsPlane(const TriangleMesh& mesh, int primitiveId) {
    valid = primitiveId >= 0 && static_cast<std::size_t>(primitiveId) < mesh.triangles.size();
    if (!valid) return;
    const auto& tri = mesh.triangles[static_cast<std::size_t>(primitiveId)];
    p0 = mesh.positions[tri[0]];
    e1 = mesh.positions[tri[1]] - p0;
    e2 = mesh.positions[tri[2]] - p0;
    // det = |e1||e2| sin(angle between the ray and the plane) sin(the triangle's angle):
    // near zero the plane is seen edge-on or the triangle is degenerate.
    edgeOn = 1e-7f * length(e1) * length(e2);
}

bool TriangleOnItsPlane::meet(const Ray& ray, float& t, float& u, float& v) const {
    // Möller-Trumbore without its range tests: the ray against the plane, in
    // the triangle's barycentrics.
    const Vec3 p = cross(ray.direction, e2);
    const float det = dot(e1, p);
    if (!(std::fabs(det) > edgeOn)) return false;
    const float inverse = 1.0f / det;
    const Vec3 s = ray.origin - p0;
    u = dot(s, p) * inverse;
    const Vec3 q = cross(s, e1);
    v = dot(ray.direction, q) * inverse;
    t = dot(e2, q) * inverse;
    return t > 0.0f && u >= -kTriangleSlack && v >= -kTriangleSlack && 1.0f - u - v >= -kTriangleSlack;
}

std::optional<TraceHit> hitOnPrimitive(const SceneObject& object, int objectId, int primitiveId, const Ray& ray,
                                       float expectedT) {
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) return hitOnSphere(*sphere, objectId, ray, expectedT);
    return hitOnTriangle(TriangleOnItsPlane(*std::get<MeshShape>(object.shape).mesh, primitiveId), objectId,
                         primitiveId, ray);
}

std::optional<TraceHit> PrimitiveHits::hit(const SceneObject& object, int objectId, int primitiveId, const Ray& ray,
                                           float expectedT) {
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) return hitOnSphere(*sphere, objectId, ray, expectedT);
    if (objectId != object_ || primitiveId != primitive_) {
        triangle_ = TriangleOnItsPlane(*std::get<MeshShape>(object.shape).mesh, primitiveId);
        object_ = objectId;
        primitive_ = primitiveId;
    }
    return hitOnTriangle(triangle_, objectId, primitiveId, ray);
}

}  // namespace raycache
