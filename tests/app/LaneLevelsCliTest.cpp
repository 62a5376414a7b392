// The lane code gives the same bits at every x86-64 level it is compiled
// for (core/LaneLevels.h): the program run with RAYCACHE_LANES narrowed to
// avx2 and to baseline writes byte-identical images to its widest run, for
// scenes with spheres, meshes, textures, glass, concave mirrors and every
// light kind, uncached and with CCT. Embree is pinned to one level for these
// runs (RAYCACHE_EMBREE_ISA): its kernels at different widths disagree on a
// rare ray that grazes an edge, and a narrowed RAYCACHE_LANES narrows Embree
// too. On a
// processor without AVX-512 the narrower runs are the same run, and the test
// still checks the rest; in a build with RAYCACHE_BASELINE_LANES (asan, tsan,
// fuzz) every run is the baseline one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "CliScratchTest.h"
#include "core/LaneInstructionSet.h"

namespace fs = std::filesystem;

namespace {

class LaneLevelsCli : public raycache::test::CliScratchTest {
protected:
    LaneLevelsCli() : CliScratchTest("raycache-lane-levels-") {}

    // The bytes of the image `raycache render <args>` writes with the
    // environment `env` ("NAME=value ...", or empty).
    std::string render(const std::string& env, const std::string& args) {
        const fs::path out = dir_ / "frame.exr";
        fs::remove(out);
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
            const std::string pinned = "RAYCACHE_EMBREE_ISA=baseline ";
            const std::string widest = render(pinned, args);
            ASSERT_FALSE(widest.empty()) << scene;
            for (const char* level : {"avx2", "baseline"})
                EXPECT_TRUE(render(pinned + "RAYCACHE_LANES=" + level + " ", args) == widest)
                    << scene << " " << technique << " at " << level;
        }
}

// A narrowed lane level stands for a processor without the wider
// instructions, so Embree gets no wider ones either: the image of an avx2 run
// is the image of the widest lanes with Embree bounded to avx2. On an AVX-512
// processor this room image differs in 4 pixels when Embree keeps AVX-512,
// so the test fails if the narrowing stops reaching Embree.
TEST_F(LaneLevelsCli, NarrowedLanesNarrowEmbreeToo) {
    if (raycache::builtWithBaselineLanes()) GTEST_SKIP() << "one lane level in this build: nothing narrows";
    const std::string args = "--scene room --width 83 --height 61 --frames 1 --path static";
    const std::string narrowed = render("RAYCACHE_LANES=avx2 ", args);
    ASSERT_FALSE(narrowed.empty());
    EXPECT_TRUE(narrowed == render("RAYCACHE_EMBREE_ISA=avx2 ", args));
}

TEST_F(LaneLevelsCli, VersionSaysWhatEmbreeMayUse) {
    const auto version = [this](const std::string& env) {
        const auto result = raycache::test::runShell(env + std::string(RAYCACHE_BINARY) + " --version",
                                                     dir_ / "stderr.txt");
        EXPECT_EQ(result.exitCode, 0) << result.err;
        return result.out;
    };
    EXPECT_NE(version("RAYCACHE_EMBREE_ISA=avx2 ").find("Embree instructions: at most avx2 (RAYCACHE_EMBREE_ISA)"),
              std::string::npos);
    if (raycache::builtWithBaselineLanes()) return;  // one level: nothing narrows
    const std::string narrowed = version("RAYCACHE_LANES=baseline ");
    const bool processorIsBaseline = narrowed.find("lanes: x86-64 (baseline)") != std::string::npos;
    if (!processorIsBaseline) {
        EXPECT_NE(narrowed.find("Embree instructions: at most baseline (RAYCACHE_LANES)"), std::string::npos)
            << narrowed;
    }
    EXPECT_NE(version("").find("Embree instructions: the processor's widest"), std::string::npos);
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
