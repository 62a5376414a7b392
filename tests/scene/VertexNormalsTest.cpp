#include <gtest/gtest.h>

#include <cmath>

#include "scene/VertexNormals.h"

namespace raycache {
namespace {

void expectUnit(const Vec3& n) {
    EXPECT_TRUE(isFinite(n)) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(length(n), 1.0f, 1e-6f);
}

void expectNear(const Vec3& got, double x, double y, double z) {
    EXPECT_NEAR(got.x, x, 1e-6);
    EXPECT_NEAR(got.y, y, 1e-6);
    EXPECT_NEAR(got.z, z, 1e-6);
}

// Two triangles meet at the origin: one of area 2 facing +z, one of area
// 1/2 facing +y. Weighted by area the origin's normal is (0, 1/2, 2)
// normalized, (0, 1, 4)/sqrt(17); an unweighted mean would give (0, 1, 1)/sqrt(2).
TEST(VertexNormals, EachTriangleWeighsByItsArea) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, {1, 0, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 3, 4}};
    const std::vector<Vec3> n = areaWeightedNormals(mesh);
    ASSERT_EQ(n.size(), 5u);
    const double s = std::sqrt(17.0);
    expectNear(n[0], 0.0, 1.0 / s, 4.0 / s);
    // A vertex of one triangle only takes that triangle's normal.
    expectNear(n[1], 0, 0, 1);
    expectNear(n[2], 0, 0, 1);
    expectNear(n[3], 0, 1, 0);
    expectNear(n[4], 0, 1, 0);
    for (const Vec3& v : n) expectUnit(v);
}

// The same triangle twice, facing both ways: the sums vanish, and every
// corner takes the normal of its largest triangle (the first of equals).
TEST(VertexNormals, CancellingTrianglesGiveAFaceNormalNotNaN) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 1}};
    for (const Vec3& v : areaWeightedNormals(mesh)) expectNear(v, 0, 0, 1);
    for (const Vec3& v : smoothNormalsByPosition(mesh)) expectNear(v, 0, 0, 1);
}

// A vertex no triangle with area uses is never shaded; it still gets a unit normal.
TEST(VertexNormals, VertexOfNoTriangleWithAreaGetsAUnitNormal) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}, {6, 6, 6}};
    mesh.triangles = {{0, 1, 2}, {3, 3, 4}};
    const std::vector<Vec3> n = areaWeightedNormals(mesh);
    expectNear(n[3], 0, 1, 0);
    expectNear(n[4], 0, 1, 0);
    for (const Vec3& v : n) expectUnit(v);
}

// Cross products beyond the float range overflow the sum: the corner falls
// back to its largest triangle's normal, computed in double precision.
TEST(VertexNormals, OverflowingSumsStayFinite) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {3e30f, 0, 0}, {0, 3e30f, 0}};
    mesh.triangles = {{0, 1, 2}};
    for (const Vec3& v : areaWeightedNormals(mesh)) expectNear(v, 0, 0, 1);
}

// A roof of two triangles whose ridge vertices are stored twice (as a file
// splits them for texture coordinates). By vertex each side keeps its own
// normal; by position the ridge is smooth: the two unit-area sides' sum.
TEST(VertexNormals, ByPositionSmoothsAcrossSplitVertices) {
    TriangleMesh mesh;
    // Ridge along x at y = 1; sides slope down to z = +1 and z = -1.
    mesh.positions = {{0, 1, 0}, {1, 1, 0}, {0, 0, 1},    // front side
                      {0, 1, 0}, {1, 1, 0}, {0, 0, -1}};  // back side, its ridge stored again
    mesh.triangles = {{0, 2, 1}, {3, 4, 5}};
    const double r = 1.0 / std::sqrt(2.0);
    const std::vector<Vec3> own = areaWeightedNormals(mesh);
    expectNear(own[0], 0, r, r);
    expectNear(own[3], 0, r, -r);
    const std::vector<Vec3> smooth = smoothNormalsByPosition(mesh);
    expectNear(smooth[0], 0, 1, 0);
    expectNear(smooth[1], 0, 1, 0);
    expectNear(smooth[3], 0, 1, 0);
    expectNear(smooth[4], 0, 1, 0);
    // Vertices stored once keep their triangle's normal.
    expectNear(smooth[2], 0, r, r);
    expectNear(smooth[5], 0, r, -r);
}

// Without repeated positions both rules are the same, bit for bit.
TEST(VertexNormals, ByPositionEqualsByVertexWithoutRepeats) {
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0.3f}, {0, 1, 0.1f}, {1, 1, 0.7f}, {2, 0.5f, -0.2f}};
    mesh.triangles = {{0, 1, 2}, {1, 3, 2}, {1, 4, 3}};
    EXPECT_EQ(smoothNormalsByPosition(mesh), areaWeightedNormals(mesh));
}

}  // namespace
}  // namespace raycache
