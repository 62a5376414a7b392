#include "scene/MeshLoader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
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
    const TriangleMesh mesh = loadMeshFile(meshDir / "cube.obj").mesh;
    EXPECT_EQ(mesh.positions.size(), 8u);
    EXPECT_EQ(mesh.triangles.size(), 12u);
    EXPECT_TRUE(mesh.uvs.empty());
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    expectBounds(mesh, {-1, -1, -1}, {1, 1, 1});
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_NEAR(length(mesh.normals[i]), 1.0f, 1e-5f);
        // Smoothed corner normals of a centred cube point outward on every
        // axis. Each triangle weighs by its area, and a corner lies in one or
        // both triangles of each split quad, so a corner in one, one and two
        // triangles gets (1, 1, 2)/sqrt(6): 4/sqrt(6) = 1.633 along the position.
        const Vec3 n = mesh.normals[i], p = mesh.positions[i];
        EXPECT_GT(n.x * p.x, 0.0f);
        EXPECT_GT(n.y * p.y, 0.0f);
        EXPECT_GT(n.z * p.z, 0.0f);
        EXPECT_GT(dot(n, p), 1.63f);
    }
    EXPECT_EQ(validateMesh(mesh), "");
}

TEST(MeshLoader, GltfWithEmbeddedBufferAppliesNodeTransform) {
    const TriangleMesh mesh = loadMeshFile(meshDir / "tetrahedron.gltf").mesh;
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
    const TriangleMesh mesh = loadMeshFile(meshDir / "tetrahedron.gltf").mesh;
    const Vec3 centre{0.25f, 0.25f, 2.25f};
    for (const auto& t : mesh.triangles) {
        const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
        // Counter-clockwise from outside: the geometric normal points away from the centre.
        EXPECT_GT(dot(cross(b - a, c - a), a - centre), 0.0f);
    }
}

TEST(MeshLoader, BinaryGlbLoads) {
    const TriangleMesh mesh = loadMeshFile(meshDir / "tetrahedron.glb").mesh;
    EXPECT_EQ(mesh.positions.size(), 4u);
    EXPECT_EQ(mesh.triangles.size(), 4u);
    expectBounds(mesh, {0, 0, 0}, {1, 1, 1});
}

TEST(MeshLoader, AsciiPlyLoadsAndTriangulatesQuads) {
    const TriangleMesh mesh = loadMeshFile(meshDir / "pyramid.ply").mesh;
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

// ---- broken files Assimp would repair or read as garbage: one InputError each ----

// Writes `contents` into a fresh per-test directory and returns the path.
std::filesystem::path writeMesh(const std::string& name, const std::string& contents) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "raycache_mesh" / info->name();
    std::filesystem::create_directories(dir);
    const std::filesystem::path path = dir / name;
    std::ofstream(path, std::ios::binary) << contents;
    return path;
}

// Expects one single-line InputError naming the file (and, when given, the
// line and column) whose message contains `fragment`.
void expectRejected(const std::filesystem::path& path, const std::string& fragment, int line = 0, int column = 0) {
    try {
        const TriangleMesh mesh = loadMeshFile(path).mesh;
        ADD_FAILURE() << path << " loaded with " << mesh.triangles.size() << " triangles";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.where().file, path.string());
        EXPECT_NE(what.find(fragment), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        if (line > 0) {
            EXPECT_EQ(e.where().line, line) << what;
            EXPECT_EQ(e.where().column, column) << what;
        }
        // The scene reader adds "cannot load mesh"; the loader must not say it too.
        EXPECT_EQ(what.find("cannot load mesh"), std::string::npos) << what;
    }
}

// Four vertices of a unit square, two triangles; index buffer at byte 48.
const std::string kGltfHead =
    R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],"buffers":[{"byteLength":60,)"
    R"("uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAACAPwAAgD8AAAAA)";
const std::string kGltfTail =
    R"("}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],)"
    R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
    R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}]})";

TEST(MeshLoader, GltfSquareLoads) {
    // Indices 0 1 2, 1 3 2: the control for the broken variants below.
    const TriangleMesh mesh = loadMeshFile(writeMesh("square.gltf", kGltfHead + "AAABAAIAAQADAAIA" + kGltfTail)).mesh;
    EXPECT_EQ(mesh.triangles.size(), 2u);
    EXPECT_EQ(mesh.positions.size(), 4u);
}

TEST(MeshLoader, GltfIndexOutOfRangeIsAnErrorNotADroppedTriangle) {
    // Indices 0 1 2, 1 7 2: Assimp drops the second triangle and only logs it.
    expectRejected(writeMesh("oob.gltf", kGltfHead + "AAABAAIAAQAHAAIA" + kGltfTail), "out-of-range indices");
}

TEST(MeshLoader, GltfNormalCountMismatchIsAnError) {
    // 2 normals for 4 vertices: Assimp ignores the normals and only logs it.
    const std::string gltf =
        R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":2},"indices":1}]}],)"
        R"("buffers":[{"byteLength":84,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAA)"
        R"(AAAAAAgD8AAAAAAACAPwAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAABAAIAAQADAAIA"}],"bufferViews":[{"buffer":0,)"
        R"("byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":72,"byteLength":12},{"buffer":0,"byteOffset":48,)"
        R"("byteLength":24}],"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],)"
        R"("max":[1,1,0]},{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"},{"bufferView":2,)"
        R"("componentType":5126,"count":2,"type":"VEC3"}]})";
    expectRejected(writeMesh("normals.gltf", gltf), "Normal count");
}

TEST(MeshLoader, GltfOfOnlyDegenerateTrianglesIsAnError) {
    // Indices 0 0 1, 2 2 2: no triangle has area.
    expectRejected(writeMesh("degenerate.gltf", kGltfHead + "AAAAAAEAAgACAAIA" + kGltfTail),
                   "all 2 triangles are degenerate");
}

TEST(MeshLoader, DegenerateTrianglesBesideGoodOnesAreDroppedWithANote) {
    // Policy (docs/scene-format.md): they only spoil normals, so they are dropped and counted.
    const auto path = writeMesh("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n");
    const LoadedMesh loaded = loadMeshFile(path);
    EXPECT_EQ(loaded.mesh.triangles.size(), 1u);
    EXPECT_EQ(loaded.note, path.string() + ": dropped 1 degenerate triangle of 2");
}

TEST(MeshLoader, MissingMaterialFileIsANote) {
    const auto path = writeMesh("mtl.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    EXPECT_EQ(loadMeshFile(path).note,
              path.string() + ": material file nowhere.mtl not found; the object's material is used");
}

TEST(MeshLoader, PointsAndLinesAreLeftOutWithANote) {
    const auto path = writeMesh("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 3\nf 1 2 3\n");
    const LoadedMesh loaded = loadMeshFile(path);
    EXPECT_EQ(loaded.mesh.triangles.size(), 1u);
    EXPECT_EQ(loaded.note, path.string() + ": ignored 2 points and lines (only triangles are drawn)");
    expectRejected(writeMesh("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\n"), "");
}

TEST(MeshLoader, ObjUnknownStatementIsAnError) {
    expectRejected(writeMesh("garbage.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nhello world\nf 1 2 3\n"),
                   "unknown OBJ statement \"hello\"", 4, 1);
}

TEST(MeshLoader, ObjTextureReferenceToNothingIsAnError) {
    // Assimp accepts "f 1/1 ..." without any "vt" and invents coordinates.
    expectRejected(writeMesh("uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n"),
                   "face refers to texture coordinate 1 but the file has 0", 4, 3);
}

TEST(MeshLoader, ObjNegativeIndexBeyondTheStartIsAnError) {
    expectRejected(writeMesh("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"),
                   "face refers to vertex -4 but the file has 3", 4, 9);
}

TEST(MeshLoader, ObjRelativeIndicesAndCommentsLoad) {
    const TriangleMesh mesh =
        loadMeshFile(writeMesh("rel.obj", "# a comment\nv 0 0 0\nv 1 0 0 # x\nv 0 1 0\ng part\ns off\nf -3 -2 -1\n"))
            .mesh;
    EXPECT_EQ(mesh.triangles.size(), 1u);
}

TEST(MeshLoader, ObjVertexWithTooFewNumbersIsAnError) {
    expectRejected(writeMesh("short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n"), "needs 3 to 7 numbers, got 2", 2, 1);
}

TEST(MeshLoader, ObjNonFiniteVertexIsAnError) {
    expectRejected(writeMesh("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 nan\nf 1 2 3\n"),
                   "1 of the file's 3 vertices are not finite (infinite or NaN)");
}

const std::string kOffTriangle = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";

TEST(MeshLoader, OffTriangleLoads) {
    const TriangleMesh mesh = loadMeshFile(writeMesh("ok.off", kOffTriangle + "3 0 1 2\n")).mesh;
    EXPECT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(mesh.positions.size(), 3u);
}

TEST(MeshLoader, OffFaceWithAMissingIndexIsAnError) {
    // Assimp reads the missing index from the next line and makes up a face.
    expectRejected(writeMesh("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n"),
                   "face 0 announces 4 vertices but lists 3", 6, 1);
}

TEST(MeshLoader, OffNegativeIndexIsAnError) {
    expectRejected(writeMesh("neg.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 -1\n"),
                   "face 1 uses vertex \"-1\" but the vertices are numbered 0 to 2", 7, 7);
}

TEST(MeshLoader, OffDataAfterTheLastFaceIsAnError) {
    expectRejected(writeMesh("extra.off", kOffTriangle + "3 0 1 2\n3 0 1 2\n"),
                   "data after the last of the 1 faces the header announces", 7, 1);
}

TEST(MeshLoader, OffWithFewerFacesThanTheHeaderIsAnError) {
    expectRejected(writeMesh("few.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                   "the header promises 3 vertices and 2 faces, the file has 4 lines of data");
}

TEST(MeshLoader, OffVertexWithExtraNumbersIsAnError) {
    expectRejected(writeMesh("long.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0 9 9\n3 0 1 2\n"),
                   "vertex 2 has 5 numbers, expected 3", 5, 1);
}

}  // namespace
// Found by fuzzing (docs/testing.md): Assimp loops forever on a PLY whose
// header lines are damaged (here "proper4y" and a broken end_header), so the
// header is checked before Assimp sees the file.
TEST(MeshLoader, DamagedPlyHeaderIsOneErrorNotAHang) {
    expectRejected(meshDir / "fuzz-ply-damaged-header.ply", "unknown PLY header line \"proper4y\"", 6, 1);
    const auto path = writeMesh("no-end.ply", "ply\nformat ascii 1.0\nelement vertex 0\n");
    expectRejected(path, "no end_header", 3, 1);
    expectRejected(writeMesh("format.ply", "ply\nformat text 1.0\nend_header\n"), "expected \"format", 2, 1);
    expectRejected(writeMesh("magic.ply", "plyx\nformat ascii 1.0\nend_header\n"), "starts with a line \"ply\"", 1, 1);
    // Finding 19: an end_header line ending the file, without a line break.
    const auto findings = std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings";
    expectRejected(findings / "assimp-ply-hang-end-header-at-end-of-file.ply",
                   "the file ends after end_header, without a line break", 5, 11);
}

// Found by fuzzing (docs/testing.md, findings 14 and 16): when the readers
// for a file's extension refuse it, Assimp guesses the format from the
// content, past our checks by extension: a damaged PLY header named .gltf
// hung in its PLY reader, an OBJ-like text named .gltf made its OBJ reader
// free memory twice. Now the extension decides: no reader for it, one error.
TEST(MeshLoader, FileTheExtensionsReadersRefuseIsOneErrorNotAGuess) {
    const auto findings = std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings";
    expectRejected(findings / "assimp-ply-hang-named-gltf.gltf", "not a .gltf file");
    expectRejected(findings / "assimp-double-free-obj-guessed-from-gltf.gltf", "not a .gltf file");
    std::ifstream in(meshDir / "fuzz-ply-damaged-header.ply", std::ios::binary);
    const std::string damaged((std::istreambuf_iterator<char>(in)), {});
    expectRejected(writeMesh("damaged.glb", damaged), "not a .glb file");
    expectRejected(writeMesh("damaged.xyz", damaged), "no reader in Assimp takes the extension '.xyz'");
    std::ifstream pyramid(meshDir / "pyramid.ply", std::ios::binary);
    const std::string good((std::istreambuf_iterator<char>(pyramid)), {});
    expectRejected(writeMesh("pyramid.gltf", good), "not a .gltf file");
    EXPECT_EQ(loadMeshFile(writeMesh("pyramid.PLY", good)).mesh.triangles.size(), 6u);
}

// Found by fuzzing (docs/testing.md, finding 15): a GLB whose JSON chunk
// claims 4 GiB; Assimp allocated that before reading. A chunk claiming more
// than the file holds is refused first.
TEST(MeshLoader, GlbChunkBeyondTheFileIsOneError) {
    const auto finding = std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings" /
                         "assimp-glb-chunk-claiming-4-gib.glb";
    expectRejected(finding, "GLB chunk at byte 12 claims 4294966606 bytes, more than the 797 left in the file");
    std::ifstream in(meshDir / "tetrahedron.glb", std::ios::binary);
    std::string glb((std::istreambuf_iterator<char>(in)), {});
    EXPECT_GT(loadMeshFile(writeMesh("good.glb", glb)).mesh.triangles.size(), 0u);
    glb[12] = static_cast<char>(glb[12] + 1);  // the JSON chunk one byte longer than it is
    EXPECT_THROW(loadMeshFile(writeMesh("long.glb", glb)), InputError);
    glb.resize(glb.size() - 1);  // and the last chunk one byte short
    glb[12] = static_cast<char>(glb[12] - 1);
    expectRejected(writeMesh("short.glb", glb), "left in the file");
}

// Found by fuzzing PLY bodies (docs/testing.md, finding 11): Assimp 5.2's
// triangulation asserts, aborting the process, on a face without vertices,
// which its PLY reader makes of a corrupt binary body (four here) and of a
// face list of length 0. The faces are looked at before post-processing.
TEST(MeshLoader, PlyFaceWithoutVerticesIsOneErrorNotAnAbort) {
    const auto finding = std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings" /
                         "assimp-abort-ply-faces-without-vertices.ply";
    expectRejected(finding, "face 0 of mesh 0 has no vertices");
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
    expectRejected(writeMesh("empty-face.ply", head + "3 0 1 2\n0\n"), "face 1 of mesh 0 has no vertices");
    EXPECT_EQ(loadMeshFile(writeMesh("good.ply", head + "3 0 1 2\n3 0 2 1\n")).mesh.triangles.size(), 2u);
}

// A header line without a PLY keyword is harmless where Assimp skips it
// (before an element's properties: Blender 2.47 wrote one after the
// format line) and accepted with a note; among an element's properties it
// would end them early and the body would be misread, so it is refused.
TEST(MeshLoader, PlyHeaderLineWithoutKeywordIsANoteOutsideProperties) {
    const std::string start = "ply\nformat ascii 1.0\n";
    const std::string vertex = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string rest =
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const auto path = writeMesh("blender.ply", start + "Created by an old exporter\n" + vertex + rest);
    const LoadedMesh loaded = loadMeshFile(path);
    EXPECT_EQ(loaded.mesh.triangles.size(), 1u);
    EXPECT_EQ(loaded.note,
              path.string() + ": ignored PLY header line 3 without a keyword (\"Created by an old exporter\")");
    const std::string among = "element vertex 3\nproperty float x\nhello there\nproperty float y\nproperty float z\n";
    expectRejected(writeMesh("among.ply", start + among + rest), "unknown PLY header line \"hello\"", 5, 1);
}

// Assimp reads a truncated ASCII PLY body without a word, making up the
// missing faces (all of vertex 0): the line count is checked first.
TEST(MeshLoader, TruncatedAsciiPlyIsAnError) {
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n";
    EXPECT_EQ(loadMeshFile(writeMesh("whole.ply", head + "3 0 1 2\n3 1 3 2\n")).note, "");
    expectRejected(writeMesh("cut.ply", head + "3 0 1 2\n"),
                   "the header announces 6 lines of data (vertex 4, face 2), the file has 5", 9, 1);
}

// Found by fuzzing (docs/testing.md, findings 17 and 18): Assimp's PLY line
// reader ends a line at a NUL (or \r, \f) and then looks for the next \n past
// its buffer; a binary PLY with control bytes in its property lines made it
// free a bad pointer, an ASCII one with NULs in an element line hung it.
// Control bytes in the header are refused, with their line and column.
TEST(MeshLoader, PlyHeaderControlByteIsOneErrorNotACrashOrAHang) {
    const auto findings = std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings";
    expectRejected(findings / "assimp-bad-free-ply-garbage-property.ply", "control byte 0x1c in the PLY header", 8, 18);
    expectRejected(findings / "assimp-ply-hang-nul-in-element-line.ply", "control byte 0x00 in the PLY header", 4, 9);
}

// A binary PLY shorter than its header announces: Assimp reads on past the
// data, taking whatever its buffer holds there for geometry.
TEST(MeshLoader, TruncatedBinaryPlyIsAnError) {
    std::ifstream in(std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "corpus" / "mesh_loader" /
                         "tetrahedron_binary_ply",
                     std::ios::binary);
    const std::string seed((std::istreambuf_iterator<char>(in)), {});
    const std::string ply = seed.substr(1);  // the fuzzer's first byte picks the extension
    EXPECT_EQ(loadMeshFile(writeMesh("whole.ply", ply)).mesh.triangles.size(), 4u);
    expectRejected(writeMesh("cut.ply", ply.substr(0, ply.size() - 1)),
                   "the header announces at least 148 bytes of binary data (vertex 4, face 4), the file has 147", 13,
                   1);
}

// Headers of the PLY grammar that Debian's Assimp 5.2.5 reads into memory
// it does not own (found by reading its PLY reader; a release build aborted
// in malloc or crashed on each): a second vertex element written into the
// first one's array, a second face element likewise, and face texture
// coordinates read through vertex indices that are not there. And one
// found by fuzzing, whose element name Assimp took for a count of
// 555555555 and allocated 13 GB for.
TEST(MeshLoader, PlyHeadersAssimpWouldOverflowAreOneError) {
    const auto findings = std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings";
    const std::string start = "ply\nformat ascii 1.0\n";
    const std::string vertices = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
    const std::string data = "0 0 0\n1 0 0\n0 1 0\n";
    expectRejected(writeMesh("two-vertex.ply", start + "element vertex 1\nproperty float x\n" + vertices + faces +
                                                   "end_header\n0\n" + data + "3 0 1 2\n"),
                   "a second \"vertex\" element (the first is on line 3)", 5, 9);
    expectRejected(writeMesh("two-face.ply", start + vertices + faces + "element face 2\n" +
                                                 "property list uchar int vertex_indices\nend_header\n" + data +
                                                 "3 0 1 2\n3 0 1 2\n3 0 2 1\n"),
                   "a second \"face\" element (the first is on line 7)", 9, 9);
    const std::string textured = start + vertices + faces + "property list uchar float texcoord\nend_header\n" + data;
    expectRejected(writeMesh("no-indices.ply", start + vertices +
                                                   "element face 1\nproperty list uchar float texcoord\nend_header\n" +
                                                   data + "6 0 0 1 0 0 1\n"),
                   "a face's texcoord list needs its vertex_indices list", 8, 1);
    expectRejected(writeMesh("long-uv.ply", textured + "3 0 1 2 8 0 0 1 0 0 1 1 1\n"),
                   "face 0's list \"texcoord\" has 8 values for its 3 vertices", 14, 9);
    // Finding 20: an element name read as its count, 555555555.
    expectRejected(findings / "assimp-oom-ply-element-name-read-as-count.ply", "starts with a digit", 11, 9);
    const TriangleMesh mesh = loadMeshFile(writeMesh("uv.ply", textured + "3 0 1 2 6 0 0 1 0 0 1\n")).mesh;
    EXPECT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(mesh.uvs.size(), 3u);
}

}  // namespace raycache
