// The built-in scenes made of real meshes (scene/RealMeshScenes.h): what they
// hold, where they find their files, and one error line when a file is
// missing or broken. Their renders, cached and not: cache/RealMeshSceneCacheTest.cpp.
#include <gtest/gtest.h>

#include "CiRequirement.h"
#include "ScopedEnvironment.h"
#include "SourceTreePaths.h"
#include "TempDir.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <variant>

#include "core/Errors.h"
#include "scene/BuiltinScenes.h"
#include "scene/RealMeshScenes.h"

namespace raycache {
namespace {

namespace fs = std::filesystem;

std::size_t meshTriangles(const SceneObject& object) {
    const auto* mesh = std::get_if<MeshShape>(&object.shape);
    return mesh ? mesh->mesh->triangles.size() : 0;
}

// What every real-mesh scene promises: a mesh of the size its file has,
// caching mirrors and glass, a moving camera.
void expectRealMeshScene(const Scene& scene, std::size_t meshTriangleCount) {
    std::size_t largest = 0;
    int cachingMirrors = 0, cachingGlass = 0;
    for (const SceneObject& object : scene.objects) {
        largest = std::max(largest, meshTriangles(object));
        if (object.material.cache.technique != CacheTechnique::Cct) continue;
        cachingGlass += object.material.refracts();
        cachingMirrors += object.material.reflects() && !object.material.refracts();
    }
    EXPECT_EQ(largest, meshTriangleCount) << scene.name;
    EXPECT_GE(cachingMirrors, 1) << scene.name;
    EXPECT_GE(cachingGlass, 1) << scene.name;
    EXPECT_EQ(scene.cameraPath.kind, CameraPathKind::Orbit) << scene.name;
    EXPECT_GE(scene.defaultFrames, 30) << scene.name;
    // Every reflective or refractive object caches, as in the other built-in scenes.
    for (const SceneObject& object : scene.objects) {
        if (object.material.reflects() || object.material.refracts()) {
            EXPECT_EQ(object.material.cache.technique, CacheTechnique::Cct) << scene.name << ' ' << object.name;
        }
    }
}

TEST(RealMeshScenes, BunnyAndTeapotScenesHoldTheirMeshMirrorsAndGlass) {
    const MeshSearchPath built = builtMeshSearchPath();
    const std::optional<Scene> bunny = makeRealMeshScene("bunny-glass", built);
    ASSERT_TRUE(bunny.has_value());
    expectRealMeshScene(*bunny, 3674);  // tests/data/meshes/bunny.obj, loaded as written
    EXPECT_TRUE(bunny->notes.empty());
    const std::optional<Scene> teapot = makeRealMeshScene("teapot-mirrors", built);
    ASSERT_TRUE(teapot.has_value());
    expectRealMeshScene(*teapot, 992);
}

TEST(RealMeshScenes, NamesAreTheirOwn) {
    EXPECT_FALSE(makeRealMeshScene("room", builtMeshSearchPath()).has_value());
    for (const RealMeshSceneInfo& info : realMeshScenes()) {
        EXPECT_FALSE(makeBuiltinScene(info.name).has_value()) << info.name << " is also a scene that needs no files";
        EXPECT_FALSE(info.meshFiles.empty()) << info.name;
    }
    EXPECT_GE(realMeshScenes().size(), 3u);
}

TEST(RealMeshScenes, TheBuiltSearchPathHoldsTheCommittedMeshes) {
    const MeshSearchPath built = builtMeshSearchPath();
    EXPECT_EQ(built.find("bunny.obj"), fs::path(RAYCACHE_TEST_DATA_DIR) / "meshes" / "bunny.obj");
    EXPECT_EQ(built.find("teapot.obj"), fs::path(RAYCACHE_TEST_DATA_DIR) / "meshes" / "teapot.obj");
    EXPECT_FALSE(built.find("no-such-mesh.obj").has_value());
}

TEST(RealMeshScenes, TheEnvironmentReplacesTheSearchPath) {
    const test::ScopedEnvironment meshPath("RAYCACHE_MESH_PATH", "/first::/second/");
    const MeshSearchPath fromEnvironment = meshSearchPathFromEnvironment();
    ASSERT_EQ(fromEnvironment.directories.size(), 2u);
    EXPECT_EQ(fromEnvironment.directories[0], fs::path("/first"));
    EXPECT_EQ(fromEnvironment.directories[1], fs::path("/second/"));
    meshPath.set("");
    EXPECT_EQ(meshSearchPathFromEnvironment().directories, builtMeshSearchPath().directories);
    meshPath.unset();
    EXPECT_EQ(meshSearchPathFromEnvironment().directories, builtMeshSearchPath().directories);
}

TEST(RealMeshScenes, AMissingMeshIsOneLineNamingItAndTheInstallStep) {
    const TempDir empty;
    const MeshSearchPath nowhere{{empty.path()}};
    for (const RealMeshSceneInfo& info : realMeshScenes()) {
        const std::string missing = missingMeshFiles(info, nowhere);
        EXPECT_NE(missing.find(info.meshFiles.front()), std::string::npos) << missing;
        try {
            (void)makeRealMeshScene(info.name, nowhere);
            ADD_FAILURE() << info.name << " built without its mesh";
        } catch (const InputError& e) {
            const std::string line = e.what();
            EXPECT_EQ(line.find('\n'), std::string::npos) << line;
            EXPECT_NE(line.find("'" + info.name + "'"), std::string::npos) << line;
            EXPECT_NE(line.find(info.meshFiles.front()), std::string::npos) << line;
            EXPECT_NE(line.find(empty.path().string()), std::string::npos) << line;
            EXPECT_NE(line.find("scripts/install-deps.sh"), std::string::npos) << line;
        }
    }
}

TEST(RealMeshScenes, ABrokenMeshIsOneLineNamingTheFile) {
    const TempDir dir;
    const fs::path bunny = dir.path() / "bunny.obj";
    for (const char* content : {
             "v 0 0 0\nv 1 0 0\nf 1 2 7\n",            // a face past the last vertex
             "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n",  // flat in y: no height to scale to
         }) {
        std::ofstream(bunny) << content;
        try {
            (void)makeRealMeshScene("bunny-glass", MeshSearchPath{{dir.path()}});
            ADD_FAILURE() << "a broken bunny.obj built: " << content;
        } catch (const InputError& e) {
            const std::string line = e.what();
            EXPECT_EQ(line.find('\n'), std::string::npos) << line;
            EXPECT_NE(line.find("'bunny-glass'"), std::string::npos) << line;
            EXPECT_NE(line.find(bunny.string()), std::string::npos) << line;
        }
    }
}

TEST(RealMeshScenes, AvailableWhereTheSearchPathHasTheFiles) {
    const MeshSearchPath built = builtMeshSearchPath();
    for (const RealMeshSceneInfo& info : realMeshScenes()) {
        // The dragon is fetched, not committed: below.
        if (std::ranges::find(info.meshFiles, "dragon_vrip.ply") != info.meshFiles.end()) continue;
        EXPECT_EQ(missingMeshFiles(info, built), "") << info.name;
    }
}

// The dragon is fetched by scripts/install-deps.sh, not committed.
TEST(RealMeshScenes, DragonScenesHoldTheDragonRepaired) {
    if (!fs::is_regular_file(stanfordDragonPath())) {
        RAYCACHE_SKIP_OR_FAIL_IN_CI(stanfordDragonPath().string()
                                    << " is missing: run scripts/install-deps.sh, which fetches it");
    }
    for (const char* name : {"dragon-hall", "dragon-mirrors"}) {
        SCOPED_TRACE(name);
        const std::optional<Scene> scene = makeRealMeshScene(name, builtMeshSearchPath());
        ASSERT_TRUE(scene.has_value());
        expectRealMeshScene(*scene, 871414u - 108u);
        ASSERT_EQ(scene->notes.size(), 1u);
        EXPECT_NE(scene->notes[0].find("dropped 108 degenerate triangles of 871414"), std::string::npos)
            << scene->notes[0];
    }
}

}  // namespace
}  // namespace raycache
