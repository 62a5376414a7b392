#pragma once
// Where a ray meets one known primitive of an object, ignoring everything
// else: used to move a reprojected sample's view-dependent shading from the
// sample's own point (up to a pixel off) to the point its pixel's centre
// sees on the same surface.
#include <optional>

#include "core/Ray.h"
#include "scene/SceneObject.h"
#include "trace/TraceHit.h"

namespace raycache {

// The hit of `ray` on primitive `primitiveId` of object `objectId` alone, as
// the tracer would report it (distance, primitive, barycentrics), or nothing
// when the ray misses it. A sphere is met where it really is, at its first
// root beyond half of `expectedT` (the distance of the point being moved:
// the same wall of the sphere, also from inside it). A triangle is
// met on its plane, also a little outside its edges (barycentrics down to
// -kTriangleSlack), where the plane and the interpolated normals continue the
// surface; farther out, or on a plane seen edge-on, it is missed.
std::optional<TraceHit> hitOnPrimitive(const SceneObject& object, int objectId, int primitiveId, const Ray& ray,
                                       float expectedT);

inline constexpr float kTriangleSlack = 0.5f;

// hitOnPrimitive's triangle test with what depends on the triangle alone
// (its corner, two edges and the edge-on threshold: two square roots) made
// once, for callers that meet many rays with one triangle.
struct TriangleOnItsPlane {
    TriangleOnItsPlane() = default;  // no triangle
    // Triangle `primitiveId` of `mesh`; `valid` false when there is none.
    TriangleOnItsPlane(const TriangleMesh& mesh, int primitiveId);
    bool valid = false;
    Vec3 p0, e1, e2;
    float edgeOn = 0.0f;  // |det| at or below it: the plane seen edge-on, or a degenerate triangle

    // Where `ray` meets the triangle's plane within kTriangleSlack of its
    // edges: distance t and barycentrics (u, v); false where it does not.
    bool meet(const Ray& ray, float& t, float& u, float& v) const;
};

// hitOnPrimitive for many rays in turn, keeping the last triangle's
// TriangleOnItsPlane: neighbouring pixels' samples mostly lie on one
// triangle. The same hits.
class PrimitiveHits {
public:
    std::optional<TraceHit> hit(const SceneObject& object, int objectId, int primitiveId, const Ray& ray,
                                float expectedT);

private:
    int object_ = -1, primitive_ = -1;
    TriangleOnItsPlane triangle_;
};

}  // namespace raycache
