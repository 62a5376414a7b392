#include "render/MeshShading.h"

#include <variant>

namespace raycache {

Vec3 unitTriangleNormal(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    return normalize(cross(p1 - p0, p2 - p0));
}

TriangleShadingRecord shadingRecordOf(const TriangleMesh& mesh, std::size_t triangle) {
    const auto& tri = mesh.triangles[triangle];
    TriangleShadingRecord record;
    record.geometricNormal = unitTriangleNormal(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
    if (!mesh.normals.empty()) {
        record.normal0 = mesh.normals[tri[0]];
        record.normal1 = mesh.normals[tri[1]];
        record.normal2 = mesh.normals[tri[2]];
    }
    return record;
}

TriangleUvRecord uvRecordOf(const TriangleMesh& mesh, std::size_t triangle) {
    const auto& tri = mesh.triangles[triangle];
    if (mesh.uvs.empty()) return {};
    return {mesh.uvs[tri[0]], mesh.uvs[tri[1]], mesh.uvs[tri[2]]};
}

namespace {

// Empties `v` for `n` new elements: keeps its memory when that is enough,
// otherwise frees it before taking the new.
template <typename T>
void emptyFor(std::vector<T>& v, std::size_t n) {
    v.clear();
    if (v.capacity() < n) {
        std::vector<T>().swap(v);
        v.reserve(n);
    }
}

}  // namespace

void remakeMeshShadingRecords(std::shared_ptr<const TriangleMesh> mesh, MeshShadingRecords& records) {
    const std::size_t n = mesh->triangles.size();
    records.mesh.reset();
    records.hasNormals = !mesh->normals.empty();
    records.hasUvs = !mesh->uvs.empty();
    // push_back, not resize: each record is written once, not zeroed first.
    emptyFor(records.triangles, n);
    for (std::size_t t = 0; t < n; ++t) records.triangles.push_back(shadingRecordOf(*mesh, t));
    emptyFor(records.uvs, records.hasUvs ? n : 0);
    if (records.hasUvs)
        for (std::size_t t = 0; t < n; ++t) records.uvs.push_back(uvRecordOf(*mesh, t));
    records.mesh = std::move(mesh);
}

MeshShadingRecords makeMeshShadingRecords(std::shared_ptr<const TriangleMesh> mesh) {
    MeshShadingRecords records;
    remakeMeshShadingRecords(std::move(mesh), records);
    return records;
}

void SceneMeshShading::refresh(const Scene& scene) {
    objects_.resize(scene.objects.size());
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const MeshShape* shape = std::get_if<MeshShape>(&scene.objects[i].shape);
        if (!shape) {
            objects_[i] = {};
        } else if (objects_[i].mesh != shape->mesh) {
            remakeMeshShadingRecords(shape->mesh, objects_[i]);
        }
    }
}

}  // namespace raycache
