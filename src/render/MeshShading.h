#pragma once
// What shading reads at a triangle-mesh hit, one cache line per triangle.
// A hit on a mesh needs its triangle's geometric normal and its three vertex
// normals (and, on textured meshes, three texture coordinates). Read from
// the mesh itself these are seven scattered reads (the triangle's indices,
// three positions, three normals), which on a large scan miss the cache
// every time; the record holds them together, computed once per pose.
#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "core/Vec3.h"
#include "scene/Scene.h"
#include "scene/TriangleMesh.h"

namespace raycache {

// A triangle's unit geometric normal, normalize(cross(p1 - p0, p2 - p0)): its
// winding's side. (NaN for a triangle without area; loaded meshes have none.)
Vec3 unitTriangleNormal(const Vec3& p0, const Vec3& p1, const Vec3& p2);

struct alignas(64) TriangleShadingRecord {
    Vec3 geometricNormal;           // unitTriangleNormal of its corners
    Vec3 normal0, normal1, normal2;  // its vertex normals; zero when the mesh has none
};
static_assert(sizeof(TriangleShadingRecord) == 64);

struct TriangleUvRecord {
    std::array<float, 2> uv0, uv1, uv2;
};

// The records of one mesh, in its triangles' order.
struct MeshShadingRecords {
    std::shared_ptr<const TriangleMesh> mesh;  // the mesh they were made from (held: its address stays its own)
    bool hasNormals = false, hasUvs = false;
    std::vector<TriangleShadingRecord> triangles;
    std::vector<TriangleUvRecord> uvs;  // empty unless hasUvs
};

// The record of triangle `triangle` of `mesh`.
TriangleShadingRecord shadingRecordOf(const TriangleMesh& mesh, std::size_t triangle);
TriangleUvRecord uvRecordOf(const TriangleMesh& mesh, std::size_t triangle);

MeshShadingRecords makeMeshShadingRecords(std::shared_ptr<const TriangleMesh> mesh);

// Makes `records` over for `mesh`, in the memory they already hold when it
// is large enough: a mesh posed anew every frame (a cloth) keeps the same
// triangle count, and rewriting warm pages costs a fraction of allocating,
// zeroing and faulting in fresh ones. Memory too small is freed before the
// new is taken, so a large mesh's records are never held twice.
void remakeMeshShadingRecords(std::shared_ptr<const TriangleMesh> mesh, MeshShadingRecords& records);

// The records of every mesh object of a scene, by object index. A posed
// scene's objects get new meshes as they move (scene/ScenePose.h); refresh()
// remakes the records of those whose mesh is not the one their records were
// made from, and recordsFor() gives records only for the object's current
// mesh, so stale records are never read.
class SceneMeshShading {
public:
    explicit SceneMeshShading(const Scene& scene) { refresh(scene); }

    // Not thread-safe: call between frames.
    void refresh(const Scene& scene);

    // The records of object `objectId`'s mesh `mesh`, or null if they are
    // not made for that mesh (the object moved since the last refresh).
    const MeshShadingRecords* recordsFor(int objectId, const TriangleMesh* mesh) const {
        const auto i = static_cast<std::size_t>(objectId);
        if (!mesh || i >= objects_.size() || objects_[i].mesh.get() != mesh) return nullptr;
        return &objects_[i];
    }

private:
    std::vector<MeshShadingRecords> objects_;  // empty records for spheres
};

}  // namespace raycache
