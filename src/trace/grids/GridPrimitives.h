#pragma once
// The primitives the grids are built over, for one frame: every triangle of
// every mesh and every sphere of the posed scene, numbered consecutively
// (object by object, in object order), with the intersection tests the grids
// run. Holds pointers into the scene, which must not change while the frame
// is traced, and a copy of every triangle's corners: the grids fetch a
// triangle many times a frame (binned into every grid, tested by packets),
// and one flat array is one load where the mesh is three dependent ones.
#include <array>
#include <cstdint>
#include <vector>

#include "core/Parallel.h"
#include "core/Ray.h"
#include "scene/Scene.h"
#include "trace/TraceHit.h"
#include "trace/grids/WatertightTriangle.h"

namespace raycache {

class GridPrimitives {
public:
    GridPrimitives() = default;
    GridPrimitives(const Scene& scene, const Parallel& parallel) { rebuild(scene, parallel); }
    // The primitives of `scene`, in place: a renderer calls this every
    // frame, and the arrays keep their memory (fresh pages would be zeroed
    // by the kernel each time).
    void rebuild(const Scene& scene, const Parallel& parallel);

    std::uint32_t count() const { return count_; }
    int objectOf(std::uint32_t primitive) const { return primitiveObject_[primitive]; }
    int localIndex(std::uint32_t primitive) const {
        return static_cast<int>(primitive - firstPrimitive_[static_cast<std::size_t>(objectOf(primitive))]);
    }
    // Null for a triangle.
    const Sphere* sphere(std::uint32_t primitive) const {
        return isSphere_[primitive] ? objects_[static_cast<std::size_t>(objectOf(primitive))].sphere : nullptr;
    }
    // The world-space corners of a triangle primitive.
    void triangle(std::uint32_t primitive, Vec3& p0, Vec3& p1, Vec3& p2) const {
        const TriangleCoordinates& c = corners_[primitive];
        p0 = {c[0], c[1], c[2]};
        p1 = {c[3], c[4], c[5]};
        p2 = {c[6], c[7], c[8]};
    }
    // The same corners as nine coordinates (p0's x, y, z, then p1's, then
    // p2's), so a packet picks its axes' components by index: Vec3's
    // operator[] with an index known only at run time is two branches.
    using TriangleCoordinates = std::array<float, 9>;
    const TriangleCoordinates& triangleCoordinates(std::uint32_t primitive) const { return corners_[primitive]; }

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
    std::vector<TriangleCoordinates> corners_;  // per primitive; a sphere's are unused
    std::vector<unsigned char> isSphere_;       // per primitive
    std::uint32_t count_ = 0;
};

}  // namespace raycache
