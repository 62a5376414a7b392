#include "scene/MeshLoader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/Errors.h"

namespace raycache {
namespace {

const std::filesystem::path meshDir = std::filesystem::path(RAYCACHE_TEST_DATA_DIR) / "meshes";

void expectBounds(const TriangleMesh& mesh, Vec3 lo, Vec3 hi) {
    Vec3 mn = mesh.positions.front(), mx = mesh.positions.front();
    for (const Vec3& p : mesh.positions) {
        mn = min(mn, p);
        mx = max(mx, p);
    }
    EXPECT_EQ(mn, lo);
    EXPECT_EQ(mx, hi);
}

// Index of the vertex at `p`; Assimp may reorder vertices, so tests look them up.
std::size_t vertexAt(const TriangleMesh& mesh, Vec3 p) {
    const auto it = std::find(mesh.positions.begin(), mesh.positions.end(), p);
    EXPECT_NE(it, mesh.positions.end()) << "no vertex at " << p.x << " " << p.y << " " << p.z;
    return static_cast<std::size_t>(it - mesh.positions.begin());
}

void expectInputErrorNamingFile(const std::filesystem::path& path) {
    try {
        loadMeshFile(path);
        FAIL() << "no exception for " << path;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        EXPECT_EQ(e.where().file, path.string());
    }
}

TEST(MeshLoader, CubeObjHasSharedCornersAndOutwardNormals) {
    const TriangleMesh mesh = loadMeshFile(meshDir / "cube.obj");
    EXPECT_EQ(mesh.positions.size(), 8u);
    EXPECT_EQ(mesh.triangles.size(), 12u);
    EXPECT_TRUE(mesh.uvs.empty());
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    expectBounds(mesh, {-1, -1, -1}, {1, 1, 1});
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_NEAR(length(mesh.normals[i]), 1.0f, 1e-5f);
        // Smoothed corner normals of a centred cube point along the position.
        EXPECT_GT(dot(mesh.normals[i], mesh.positions[i]), 1.7f);
    }
    EXPECT_EQ(validateMesh(mesh), "");
}

TEST(MeshLoader, GltfWithEmbeddedBufferAppliesNodeTransform) {
    const TriangleMesh mesh = loadMeshFile(meshDir / "tetrahedron.gltf");
    EXPECT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(mesh.triangles.size(), 4u);
    EXPECT_EQ(mesh.normals.size(), 4u);
    // The node translates by (0, 0, 2).
    expectBounds(mesh, {0, 0, 2}, {1, 1, 3});
    ASSERT_EQ(mesh.uvs.size(), 4u);
    // glTF puts v = 0 at the image top; Assimp flips it to v = 0 at the bottom.
    const auto uv = [&](Vec3 p) { return mesh.uvs[vertexAt(mesh, p)]; };
    EXPECT_EQ(uv({0, 0, 2}), (std::array<float, 2>{0.0f, 1.0f}));
    EXPECT_EQ(uv({1, 0, 2}), (std::array<float, 2>{1.0f, 1.0f}));
    EXPECT_EQ(uv({0, 1, 2}), (std::array<float, 2>{0.0f, 0.0f}));
    EXPECT_EQ(uv({0, 0, 3}), (std::array<float, 2>{0.5f, 0.5f}));
}

TEST(MeshLoader, GltfTrianglesKeepTheirWinding) {
    const TriangleMesh mesh = loadMeshFile(meshDir / "tetrahedron.gltf");
    const Vec3 centre{0.25f, 0.25f, 2.25f};
    for (const auto& t : mesh.triangles) {
        const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
        // Counter-clockwise from outside: the geometric normal points away from the centre.
        EXPECT_GT(dot(cross(b - a, c - a), a - centre), 0.0f);
    }
}

TEST(MeshLoader, BinaryGlbLoads) {
    const TriangleMesh mesh = loadMeshFile(meshDir / "tetrahedron.glb");
    EXPECT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(mesh.triangles.size(), 4u);
    expectBounds(mesh, {0, 0, 0}, {1, 1, 1});
}

TEST(MeshLoader, AsciiPlyLoadsAndTriangulatesQuads) {
    const TriangleMesh mesh = loadMeshFile(meshDir / "pyramid.ply");
    EXPECT_EQ(mesh.triangles.size(), 6u);  // 4 sides + the base quad split in two
    EXPECT_EQ(mesh.positions.size(), 5u);
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    expectBounds(mesh, {-1, 0, -1}, {1, 1, 1});
    EXPECT_EQ(validateMesh(mesh), "");
}

TEST(MeshLoader, FaceWithMissingVertexThrows) { expectInputErrorNamingFile(meshDir / "broken.obj"); }

TEST(MeshLoader, EmptyFileThrows) { expectInputErrorNamingFile(meshDir / "empty.obj"); }

TEST(MeshLoader, MalformedGltfThrows) { expectInputErrorNamingFile(meshDir / "garbage.gltf"); }

TEST(MeshLoader, MissingFileThrows) { expectInputErrorNamingFile(meshDir / "no-such-mesh.obj"); }

TEST(MeshLoader, DirectoryThrows) { expectInputErrorNamingFile(meshDir); }

}  // namespace
}  // namespace raycache
