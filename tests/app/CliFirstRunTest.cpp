// What a new user meets on the first runs: output directories that do not
// exist yet, frame file numbers, thread counts, scene descriptions, and
// scene files that are absurd rather than malformed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "CliScratchTest.h"

namespace fs = std::filesystem;

namespace {

using raycache::test::lineCount;
using raycache::test::RunResult;

class CliFirstRun : public raycache::test::CliScratchTest {
protected:
    CliFirstRun() : CliScratchTest("raycache-cli-first-run-") {}
};

}  // namespace

TEST_F(CliFirstRun, RenderCreatesTheOutputAndStatsDirectories) {
    // The README's example in a fresh checkout, where out/ does not exist.
    const RunResult r =
        run("render --scene behind-0 --width 16 --height 16 --frames 2 --out " +
            (dir_ / "out" / "frames" / "f_%04d.png").string() + " --stats " + (dir_ / "out2" / "stats.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "out" / "frames" / "f_0001.png"));
    EXPECT_TRUE(fs::exists(dir_ / "out" / "frames" / "f_0002.png"));
    EXPECT_FALSE(fs::exists(dir_ / "out" / "frames" / "f_0000.png"));
    std::ifstream in(dir_ / "out2" / "stats.json");
    const nlohmann::json stats = nlohmann::json::parse(in);
    // Frames count from 1 everywhere: progress, file names, statistics.
    EXPECT_EQ(stats.at("frames").at(0).at("frame"), 1);
    EXPECT_EQ(stats.at("frames").at(1).at("frame"), 2);
    EXPECT_NE(r.out.find("frame 1/2"), std::string::npos);
    EXPECT_NE(r.out.find("frame 2/2"), std::string::npos);
}

TEST_F(CliFirstRun, FailedRenderCreatesNoDirectory) {
    const RunResult r = run("render --scene no-such-scene.json --out " + (dir_ / "new" / "x.png").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_FALSE(fs::exists(dir_ / "new"));
}

TEST_F(CliFirstRun, OutputDirectoryBlockedByAFileIsOneError) {
    std::ofstream(dir_ / "file") << "x";
    const RunResult r =
        run("render --scene behind-0 --width 8 --height 8 --frames 1 --out " + (dir_ / "file" / "x.png").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("cannot create the output directory"), std::string::npos) << r.err;
}

TEST_F(CliFirstRun, DiffCreatesTheHeatmapDirectory) {
    const RunResult render =
        run("render --scene behind-0 --width 16 --height 16 --frames 1 --out " + (dir_ / "a.png").string());
    ASSERT_EQ(render.exitCode, 0) << render.err;
    const RunResult r = run("diff " + (dir_ / "a.png").string() + " " + (dir_ / "a.png").string() + " --heatmap " +
                            (dir_ / "maps" / "d.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "maps" / "d.png"));
}

TEST_F(CliFirstRun, TooManyThreadsAreClampedWithANoteAndNothingOnStderr) {
    const RunResult r = run("render --scene behind-1 --width 16 --height 16 --frames 1 --threads 1000");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");  // oneTBB used to print a warning here
    EXPECT_NE(r.out.find("note: --threads 1000 is more than the "), std::string::npos) << r.out;
}

TEST_F(CliFirstRun, ScenesCountSpheresInGoodEnglish) {
    const RunResult r = run("scenes");
    ASSERT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("1 mirror sphere behind the camera"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("2 mirror spheres behind the camera"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("1 mirror spheres"), std::string::npos) << r.out;
}

TEST_F(CliFirstRun, DeeplyNestedSceneFileIsOneErrorLine) {
    // 200 kB of '[': used to take 21 s to reject.
    std::ofstream(dir_ / "nested.json") << std::string(200000, '[');
    const RunResult r =
        run("render --scene " + (dir_ / "nested.json").string() + " --out " + (dir_ / "o.png").string());
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1) << r.err.substr(0, 300);
    EXPECT_EQ(r.err.rfind("error: " + (dir_ / "nested.json").string() + ":1:65: /0/0/", 0), 0u) << r.err.substr(0, 300);
    EXPECT_NE(r.err.find("nested more than 64 levels deep"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir_ / "o.png"));
}
