// The real-mesh built-in scenes as a user meets them: listed by `raycache
// scenes`, marked unavailable when their mesh is not found, and one error
// line with exit 2 when rendered without it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "ShellRun.h"
#include "TempDir.h"
#include "scene/RealMeshScenes.h"

namespace fs = std::filesystem;

namespace {

// The raycache binary run with RAYCACHE_MESH_PATH set to `meshPath`.
raycache::test::RunResult runRaycacheWithMeshPath(const std::string& meshPath, const std::string& args,
                                                  const fs::path& dir) {
    return raycache::test::runShell("RAYCACHE_MESH_PATH='" + meshPath + "' " + std::string(RAYCACHE_BINARY) + " " + args,
                                    dir / "stderr.txt");
}

}  // namespace

TEST(RealMeshScenesCli, ScenesListsThemAvailableWhereTheMeshesAre) {
    const raycache::TempDir dir;
    const std::string meshes = (fs::path(RAYCACHE_TEST_DATA_DIR) / "meshes").string();
    const raycache::test::RunResult r = runRaycacheWithMeshPath(meshes, "scenes", dir.path());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("\nbunny-glass "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\nteapot-mirrors "), std::string::npos) << r.out;
    // The dragon is not in tests/data: its scenes are listed, as unavailable, each on its own line.
    for (const char* name : {"\ndragon-hall ", "\ndragon-mirrors "}) {
        const std::size_t dragon = r.out.find(name);
        ASSERT_NE(dragon, std::string::npos) << r.out;
        const std::string dragonLine = r.out.substr(dragon + 1, r.out.find('\n', dragon + 1) - dragon - 1);
        EXPECT_NE(dragonLine.find("(unavailable: dragon_vrip.ply is in none of " + meshes), std::string::npos)
            << dragonLine;
        EXPECT_NE(dragonLine.find("scripts/install-deps.sh"), std::string::npos) << dragonLine;
    }
    std::size_t unavailable = 0;
    for (std::size_t at = r.out.find("unavailable"); at != std::string::npos; at = r.out.find("unavailable", at + 1))
        ++unavailable;
    EXPECT_EQ(unavailable, 2u) << "only the dragon's two scenes are unavailable:\n" << r.out;
}

TEST(RealMeshScenesCli, RenderingWithoutTheMeshIsOneLineAndExit2) {
    const raycache::TempDir dir;
    const fs::path empty = dir.path() / "no-meshes";
    fs::create_directories(empty);
    const raycache::test::RunResult r = runRaycacheWithMeshPath(
        empty.string(), "render --scene bunny-glass --width 16 --height 16 --frames 1 --out " +
                            (dir.path() / "bunny.png").string(),
        dir.path());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(raycache::test::lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("error: built-in scene 'bunny-glass': bunny.obj is in none of " + empty.string(), 0), 0u)
        << r.err;
    EXPECT_NE(r.err.find("scripts/install-deps.sh"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir.path() / "bunny.png"));
}

TEST(RealMeshScenesCli, TheCommittedMeshesRenderWithoutSettingAnything) {
    const raycache::TempDir dir;
    const fs::path out = dir.path() / "teapot.png";
    const raycache::test::RunResult r = raycache::test::runShell(
        "env -u RAYCACHE_MESH_PATH " + std::string(RAYCACHE_BINARY) +
            " render --scene teapot-mirrors --width 24 --height 24 --frames 2 --out " + out.string(),
        dir.path() / "stderr.txt");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::is_regular_file(out));
}
