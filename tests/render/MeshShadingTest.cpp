// The per-triangle shading records (render/MeshShading.h): what each record
// holds, and that records are only handed out for the mesh they were made from.
#include <gtest/gtest.h>

#include <memory>
#include <utility>

#include "render/MeshShading.h"

namespace raycache {
namespace {

std::shared_ptr<TriangleMesh> twoTriangles(bool normals, bool uvs) {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->positions = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {0, 0, 4}};
    mesh->triangles = {{0, 1, 2}, {0, 3, 1}};
    if (normals) mesh->normals = {{0, 0, 1}, {0.6f, 0, 0.8f}, {0, 0.8f, 0.6f}, {0, -1, 0}};
    if (uvs) mesh->uvs = {{0, 0}, {1, 0}, {0, 1}, {0.5f, 0.25f}};
    return mesh;
}

TEST(MeshShading, RecordHoldsTheTrianglesUnitNormalAndItsVertexAttributes) {
    const auto mesh = twoTriangles(true, true);
    const MeshShadingRecords records = makeMeshShadingRecords(mesh);
    ASSERT_EQ(records.triangles.size(), 2u);
    ASSERT_EQ(records.uvs.size(), 2u);
    EXPECT_TRUE(records.hasNormals);
    EXPECT_TRUE(records.hasUvs);
    // (2,0,0) x (0,3,0) points along +z; (0,0,4) x (2,0,0) along +y.
    EXPECT_EQ(records.triangles[0].geometricNormal, (Vec3{0, 0, 1}));
    EXPECT_EQ(records.triangles[1].geometricNormal, (Vec3{0, 1, 0}));
    EXPECT_EQ(records.triangles[1].normal0, mesh->normals[0]);
    EXPECT_EQ(records.triangles[1].normal1, mesh->normals[3]);
    EXPECT_EQ(records.triangles[1].normal2, mesh->normals[1]);
    EXPECT_EQ(records.uvs[1].uv1, mesh->uvs[3]);
    EXPECT_EQ(records.uvs[1].uv2, mesh->uvs[1]);
}

TEST(MeshShading, MeshWithoutNormalsOrUvsHasZeroNormalsAndNoUvRecords) {
    const MeshShadingRecords records = makeMeshShadingRecords(twoTriangles(false, false));
    EXPECT_FALSE(records.hasNormals);
    EXPECT_FALSE(records.hasUvs);
    EXPECT_TRUE(records.uvs.empty());
    EXPECT_EQ(records.triangles[0].normal0, Vec3{});
    EXPECT_EQ(records.triangles[0].normal2, Vec3{});
}

TEST(MeshShading, RecordsAreOnlyGivenForTheMeshTheyWereMadeFrom) {
    Scene scene;
    scene.objects.resize(2);
    scene.objects[0].shape = Sphere{{0, 0, 0}, 1.0f};
    const auto first = twoTriangles(true, false);
    scene.objects[1].shape = MeshShape{first};
    SceneMeshShading shading(scene);
    EXPECT_EQ(shading.recordsFor(0, nullptr), nullptr);  // a sphere has none
    const MeshShadingRecords* made = shading.recordsFor(1, first.get());
    ASSERT_NE(made, nullptr);
    EXPECT_EQ(made->triangles[0].geometricNormal, (Vec3{0, 0, 1}));

    // The object moves: a posed scene gives it a new mesh. Until the next
    // refresh its old records are not handed out for the new mesh.
    auto moved = std::make_shared<TriangleMesh>(*first);
    for (Vec3& p : moved->positions) p = Vec3{p.z, p.y, p.x};  // mirrored: the winding turns over
    scene.objects[1].shape = MeshShape{moved};
    EXPECT_EQ(shading.recordsFor(1, moved.get()), nullptr);
    shading.refresh(scene);
    const MeshShadingRecords* remade = shading.recordsFor(1, moved.get());
    ASSERT_NE(remade, nullptr);
    EXPECT_EQ(remade->triangles[0].geometricNormal, (Vec3{-1, 0, 0}));
    EXPECT_EQ(shading.recordsFor(1, first.get()), nullptr);
}

TEST(MeshShading, RemadeRecordsEqualFreshOnesWhateverTheyHeldBefore) {
    // Remaking reuses the old records' memory: nothing of the old mesh may
    // survive, whether the new one has more, as many or fewer attributes.
    const auto withAll = twoTriangles(true, true);
    const auto bare = twoTriangles(false, false);
    auto bigger = std::make_shared<TriangleMesh>(*withAll);
    bigger->triangles.push_back({1, 2, 3});
    for (const auto& [before, after] : {std::pair{withAll, bare}, std::pair{bare, withAll},
                                        std::pair{withAll, bigger}, std::pair{bigger, withAll}}) {
        MeshShadingRecords records = makeMeshShadingRecords(before);
        remakeMeshShadingRecords(after, records);
        const MeshShadingRecords fresh = makeMeshShadingRecords(after);
        EXPECT_EQ(records.mesh, after);
        EXPECT_EQ(records.hasNormals, fresh.hasNormals);
        EXPECT_EQ(records.hasUvs, fresh.hasUvs);
        ASSERT_EQ(records.triangles.size(), fresh.triangles.size());
        ASSERT_EQ(records.uvs.size(), fresh.uvs.size());
        for (std::size_t t = 0; t < fresh.triangles.size(); ++t) {
            EXPECT_EQ(records.triangles[t].geometricNormal, fresh.triangles[t].geometricNormal);
            EXPECT_EQ(records.triangles[t].normal0, fresh.triangles[t].normal0);
            EXPECT_EQ(records.triangles[t].normal1, fresh.triangles[t].normal1);
            EXPECT_EQ(records.triangles[t].normal2, fresh.triangles[t].normal2);
        }
        for (std::size_t t = 0; t < fresh.uvs.size(); ++t) {
            EXPECT_EQ(records.uvs[t].uv0, fresh.uvs[t].uv0);
            EXPECT_EQ(records.uvs[t].uv2, fresh.uvs[t].uv2);
        }
    }
}

}  // namespace
}  // namespace raycache
