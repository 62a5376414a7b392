// The lane code gives the same bits at every x86-64 level it is compiled
// for (core/LaneLevels.h): the program run with RAYCACHE_LANES narrowed to
// avx2 and to baseline writes byte-identical images to its widest run, for
// scenes with spheres, meshes, textures, glass, concave mirrors and every
// light kind, uncached and with CCT. On a processor without AVX-512 the
// narrower runs are the same run, and the test still checks the rest; in a
// build with RAYCACHE_BASELINE_LANES (asan, tsan, fuzz) every run is the
// baseline one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "CliScratchTest.h"

namespace fs = std::filesystem;

namespace {

class LaneLevelsCli : public raycache::test::CliScratchTest {
protected:
    LaneLevelsCli() : CliScratchTest("raycache-lane-levels-") {}

    // The bytes of the image `raycache render <args>` writes with RAYCACHE_LANES=level.
    std::string render(const std::string& level, const std::string& args) {
        const fs::path out = dir_ / ("frame-" + level + ".exr");
        const std::string env = level.empty() ? "" : "RAYCACHE_LANES=" + level + " ";
        const auto result = raycache::test::runShell(env + std::string(RAYCACHE_BINARY) + " render " + args +
                                                         " --out " + out.string(),
                                                     dir_ / "stderr.txt");
        EXPECT_EQ(result.exitCode, 0) << result.err;
        std::ifstream in(out, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }
};

TEST_F(LaneLevelsCli, EveryLevelWritesTheSameImage) {
    for (const char* scene : {"room", "glass", "bowl", "shapes", "grid-8", "light-sweep", "cloth"})
        for (const char* technique : {"none", "cct"}) {
            const std::string args = std::string("--scene ") + scene +
                                     " --width 83 --height 61 --frames 2 --path static --technique " + technique;
            const std::string widest = render("", args);
            ASSERT_FALSE(widest.empty()) << scene;
            for (const char* level : {"avx2", "baseline"})
                EXPECT_TRUE(render(level, args) == widest) << scene << " " << technique << " at " << level;
        }
}

TEST_F(LaneLevelsCli, VersionSaysWhichLevelTheHitLanesRun) {
    const auto result =
        raycache::test::runShell("RAYCACHE_LANES=baseline " + std::string(RAYCACHE_BINARY) + " --version",
                                 dir_ / "stderr.txt");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("lanes:"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("baseline"), std::string::npos) << result.out;
}

}  // namespace
