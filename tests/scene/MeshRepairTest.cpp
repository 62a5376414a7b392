#include <gtest/gtest.h>

#include "UnitNormals.h"

#include <cmath>
#include <limits>

#include "scene/MeshRepair.h"

namespace raycache {
namespace {

// Two good triangles (areas 2 and 1/2, facing +z and +y, meeting at vertex
// 0), a zero-area triangle with three distinct corners on a line, one that
// uses a vertex twice, and vertex 6, used only by the degenerate ones.
TriangleMesh meshWithDegenerateTriangles() {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, {1, 0, 0}, {3, 0, 0}, {7, 7, 7}};
    mesh.triangles = {{0, 1, 2}, {1, 4, 5}, {0, 3, 4}, {6, 6, 2}};
    return mesh;
}

TEST(MeshRepair, DegenerateTrianglesAreDroppedAndCounted) {
    TriangleMesh mesh = meshWithDegenerateTriangles();
    const MeshRepairs repairs = repairMesh(mesh);
    const std::vector<std::array<std::uint32_t, 3>> kept = {{0, 1, 2}, {0, 3, 4}};
    EXPECT_EQ(mesh.triangles, kept);
    EXPECT_EQ(repairs.degenerateTriangles, 2u);
    EXPECT_EQ(repairs.phrases(), std::vector<std::string>{"dropped 2 degenerate triangles of 4"});
}

// Normals the file did not have are made from the kept triangles, weighted
// by area (vertex 0: (0, 1/2, 2) normalized), and are unit length and
// finite everywhere, also at vertex 6, whose only triangle was dropped.
// Making them is not a repair: no phrase.
TEST(MeshRepair, MissingNormalsAreAreaWeightedFiniteAndUnit) {
    TriangleMesh mesh = meshWithDegenerateTriangles();
    repairMesh(mesh);
    expectUnitNormals(mesh, 1e-6f);
    const double s = std::sqrt(17.0);
    EXPECT_NEAR(mesh.normals[0].y, 1.0 / s, 1e-6);
    EXPECT_NEAR(mesh.normals[0].z, 4.0 / s, 1e-6);
    EXPECT_EQ(mesh.normals[1], (Vec3{0, 0, 1}));
    EXPECT_EQ(mesh.normals[3], (Vec3{0, 1, 0}));
    EXPECT_EQ(mesh.normals[6], (Vec3{0, 1, 0}));
}

// Of given normals, only the zero-length and non-finite ones are made
// again (by area, from the triangles at that vertex); the others stay as
// given, bit for bit, even when not of unit length.
TEST(MeshRepair, InvalidGivenNormalsAreRegeneratedOthersKept) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, {1, 0, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 3, 4}};
    const float nan = std::numeric_limits<float>::quiet_NaN();
    mesh.normals = {{0, 0, 0}, {0.1f, 0.2f, 0.9f}, {nan, 0, 1}, {0, 2, 0}, {0, 1, 0}};
    const MeshRepairs repairs = repairMesh(mesh);
    const double s = std::sqrt(17.0);
    EXPECT_NEAR(mesh.normals[0].y, 1.0 / s, 1e-6);
    EXPECT_NEAR(mesh.normals[0].z, 4.0 / s, 1e-6);
    EXPECT_EQ(mesh.normals[1], (Vec3{0.1f, 0.2f, 0.9f}));
    EXPECT_EQ(mesh.normals[2], (Vec3{0, 0, 1}));
    EXPECT_EQ(mesh.normals[3], (Vec3{0, 2, 0}));
    EXPECT_EQ(repairs.phrases(),
              std::vector<std::string>{"regenerated 2 invalid normals of 5 (1 zero-length, 1 not finite)"});
}

TEST(MeshRepair, NormalsMissingFromSomePartsAreMadeAndSaid) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 0, -1}};
    mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
    mesh.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {}, {}, {}};
    const MeshRepairs repairs = repairMesh(mesh, {false, false, false, true, true, true});
    for (std::size_t v = 3; v < 6; ++v) EXPECT_EQ(mesh.normals[v], (Vec3{0, 1, 0}));
    EXPECT_EQ(repairs.phrases(), std::vector<std::string>{"regenerated 3 missing normals of 6"});
}

TEST(MeshRepair, UnusableTextureCoordinatesAreIgnored) {
    TriangleMesh same = meshWithDegenerateTriangles();
    same.uvs.assign(same.positions.size(), {0.5f, 0.5f});
    const MeshRepairs sameRepairs = repairMesh(same);
    EXPECT_TRUE(same.uvs.empty());
    EXPECT_EQ(sameRepairs.phrases().back(), "ignored its texture coordinates (all 7 the same)");

    TriangleMesh nonFinite = meshWithDegenerateTriangles();
    nonFinite.uvs.assign(nonFinite.positions.size(), {0.25f, 0.75f});
    nonFinite.uvs[2] = {std::numeric_limits<float>::infinity(), 0.0f};
    nonFinite.uvs[3] = {0.5f, 0.5f};
    const MeshRepairs nonFiniteRepairs = repairMesh(nonFinite);
    EXPECT_TRUE(nonFinite.uvs.empty());
    EXPECT_EQ(nonFiniteRepairs.phrases().back(), "ignored its texture coordinates (1 of 7 not finite)");
}

// A mesh with nothing wrong comes out as it went in, with no phrase.
TEST(MeshRepair, SoundMeshIsUnchanged) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5f}};
    mesh.triangles = {{0, 1, 2}, {1, 3, 2}};
    mesh.normals = {{0, 0, 1}, {0, 0.1f, 0.9f}, {0, 0, 1}, {0.3f, 0, 0.9f}};
    mesh.uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    const TriangleMesh before = mesh;
    EXPECT_TRUE(repairMesh(mesh).phrases().empty());
    EXPECT_EQ(mesh.positions, before.positions);
    EXPECT_EQ(mesh.normals, before.normals);
    EXPECT_EQ(mesh.uvs, before.uvs);
    EXPECT_EQ(mesh.triangles, before.triangles);
}

// Nothing but degenerate triangles: nothing is dropped, so the loader's
// validation refuses the mesh with the count.
TEST(MeshRepair, OnlyDegenerateTrianglesAreLeftForTheLoaderToRefuse) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 0, 1}};
    EXPECT_TRUE(repairMesh(mesh).phrases().empty());
    EXPECT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(validateMesh(mesh), "all 2 triangles are degenerate (zero area)");
}

}  // namespace
}  // namespace raycache
