#pragma once
// The primitives the grids are built over, for one frame: every triangle of
// every mesh and every sphere of the posed scene, numbered consecutively
// (object by object, in object order), with the intersection tests the grids
// run. Holds pointers into the scene, which must not change while the frame
// is traced.
#include <cstdint>
#include <vector>

#include "core/Ray.h"
#include "scene/Scene.h"
#include "trace/TraceHit.h"
#include "trace/grids/WatertightTriangle.h"

namespace raycache {

class GridPrimitives {
public:
    explicit GridPrimitives(const Scene& scene);

    std::uint32_t count() const { return count_; }
    int objectOf(std::uint32_t primitive) const { return primitiveObject_[primitive]; }
    int localIndex(std::uint32_t primitive) const {
        return static_cast<int>(primitive - firstPrimitive_[static_cast<std::size_t>(objectOf(primitive))]);
    }
    // Null for a triangle.
    const Sphere* sphere(std::uint32_t primitive) const;
    // The world-space corners of a triangle primitive.
    void triangle(std::uint32_t primitive, Vec3& p0, Vec3& p1, Vec3& p2) const;

    // The primitive's hit on `ray` if it is nearer than `best` (ties on
    // distance go to the smaller object id, then primitive id, so the answer
    // does not depend on the order primitives are tested in).
    void intersect(std::uint32_t primitive, const Ray& ray, const WatertightRay& watertight, TraceHit& best) const;
    // The rule intersect() applies: is a hit at t on (object, primitive) nearer than `best`?
    static bool nearer(float t, int object, int primitive, const TraceHit& best) {
        if (!best.hit()) return true;
        if (t != best.t) return t < best.t;
        return object != best.objectId ? object < best.objectId : primitive < best.primitiveId;
    }
    // True if the primitive meets the ray anywhere in its segment.
    bool occludes(std::uint32_t primitive, const Ray& ray, const WatertightRay& watertight) const;

private:
    struct ObjectGeometry {
        const Sphere* sphere = nullptr;
        const TriangleMesh* mesh = nullptr;
    };
    std::vector<ObjectGeometry> objects_;
    std::vector<std::uint32_t> firstPrimitive_;  // per object, and the total at the end
    std::vector<int> primitiveObject_;
    std::uint32_t count_ = 0;
};

}  // namespace raycache
