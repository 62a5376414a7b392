// The raycache binary as a user meets it: exit codes, one-line errors, and no
// partial output files.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "TextPattern.h"
#include "TempDir.h"
#include "ShellRun.h"
#include "scene/ImageLoader.h"

namespace fs = std::filesystem;

namespace {

using raycache::test::lineCount;
using raycache::test::RunResult;

// Runs the raycache binary with `args` (already shell-quoted where needed).
RunResult runRaycache(const std::string& args, const fs::path& dir) {
    return raycache::test::runShell(std::string(RAYCACHE_BINARY) + " " + args, dir / "stderr.txt");
}

// The value of the line "<key>: <value>" of `text`, empty if there is none.
std::string lineValue(const std::string& text, const std::string& key) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind(key + ": ", 0) == 0) return line.substr(key.size() + 2);
    return {};
}

class Cli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = raycache::scratchPathForThisTest("raycache-cli-");
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    // Files in the temp dir other than our captured stderr.
    std::vector<std::string> outputs() const {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir_))
            if (e.path().filename() != "stderr.txt") names.push_back(e.path().filename().string());
        return names;
    }
    fs::path dir_;
};

}  // namespace

TEST_F(Cli, ScenesListsOneLinePerBuiltinScene) {
    const RunResult r = runRaycache("scenes", dir_);
    EXPECT_EQ(r.exitCode, 0);
    // behind-N, grid-N, the two 32-sphere walls, 5 others, 4 animated, 4 of
    // real meshes (each listed, available or not: RealMeshScenesCliTest.cpp)
    EXPECT_EQ(lineCount(r.out), 7 + 6 + 2 + 5 + 4 + 4);
    EXPECT_NE(r.out.find("behind-32"), std::string::npos);
    EXPECT_NE(r.out.find("light-sweep"), std::string::npos);
    EXPECT_NE(r.out.find("parallax"), std::string::npos);
}

TEST_F(Cli, AnimatedSceneReportsItsSceneUpdateAndTimeInTheStats) {
    const RunResult r = runRaycache("render --scene orbit --frames 2 --width 32 --height 32 --time 0.5 --fps 10 "
                                    "--stats " + (dir_ / "stats.json").string(),
                                    dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("scene update: 4 objects, 0 lights changed"), std::string::npos) << r.out;
    std::ifstream in(dir_ / "stats.json");
    const std::string stats((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(stats.find("\"time\": 0.6"), std::string::npos) << stats;  // frame 2 at 0.5 + 1/10 s
    EXPECT_NE(stats.find("\"scene_update\""), std::string::npos);
}

TEST_F(Cli, BadTimeOrFpsIsOneLineAndExit2) {
    for (const char* args : {"render --scene orbit --time nan", "render --scene orbit --fps 0",
                             "render --scene orbit --fps -3", "render --scene orbit --time 1e9"}) {
        const RunResult r = runRaycache(args, dir_);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << ": " << r.err;
    }
}

TEST_F(Cli, HelpWorksForEveryCommand) {
    for (const char* args : {"--help", "render --help", "cache-view --help", "scenes --help"}) {
        const RunResult r = runRaycache(args, dir_);
        EXPECT_EQ(r.exitCode, 0) << args;
        EXPECT_NE(r.out.find("Usage"), std::string::npos) << args;
    }
    EXPECT_NE(runRaycache("--help", dir_).out.find("--version"), std::string::npos);
}

TEST_F(Cli, VersionPrintsTheBuildWithoutASubcommand) {
    const RunResult r = runRaycache("--version", dir_);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(r.out.rfind("raycache ", 0), 0u) << r.out;
    // Twelve hex digits, "-dirty" when built with uncommitted changes;
    // "unknown" only outside a git checkout.
    EXPECT_TRUE(test::TextPattern("[0-9a-f]{12}(-dirty)?|unknown").matchesWhole(lineValue(r.out, "commit"))) << r.out;
    EXPECT_TRUE(test::TextPattern("3\\.[0-9]+\\.[0-9]+").matchesWhole(lineValue(r.out, "Embree"))) << r.out;
    for (const char* key : {"build", "Embree instructions", "oneTBB", "Assimp", "OpenEXR", "lanes"})
        EXPECT_NE(lineValue(r.out, key), "") << key << " in " << r.out;
    EXPECT_EQ(lineValue(r.out, "lanes").rfind("x86-64", 0), 0u) << r.out;
}

// One place gathers the build facts: the statistics say what --version says.
TEST_F(Cli, StatsCarryTheVersionThatVersionPrints) {
    const std::string version = runRaycache("--version", dir_).out;
    const fs::path stats = dir_ / "stats.json";
    const RunResult r = runRaycache("render --scene behind-0 --width 8 --height 8 --frames 1 --stats " + stats.string(),
                                    dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in(stats);
    const nlohmann::json v = nlohmann::json::parse(in).at("version");
    EXPECT_EQ("raycache " + v.at("raycache").get<std::string>(), version.substr(0, version.find('\n')));
    EXPECT_EQ(v.at("git_commit"), lineValue(version, "commit"));
    EXPECT_EQ(v.at("build_type").get<std::string>() + ", " + v.at("compiler").get<std::string>(),
              lineValue(version, "build"));
    EXPECT_EQ(v.at("embree"), lineValue(version, "Embree"));
    EXPECT_EQ(v.at("embree_instructions"), lineValue(version, "Embree instructions"));
    EXPECT_EQ(v.at("tbb"), lineValue(version, "oneTBB"));
    EXPECT_EQ(v.at("assimp"), lineValue(version, "Assimp"));
    EXPECT_EQ(v.at("openexr"), lineValue(version, "OpenEXR"));
    EXPECT_EQ(v.at("lanes"), lineValue(version, "lanes"));
    EXPECT_TRUE(v.at("baseline_lanes_build").is_boolean());
}

TEST_F(Cli, RenderWritesTheLastFrameAndPrintsTimings) {
    const fs::path out = dir_ / "frame.png";
    const RunResult r = runRaycache("render --scene grid-4 --width 32 --height 24 --frames 3 --out " + out.string() +
                                        " --stats " + (dir_ / "stats.json").string(),
                                    dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(out));
    EXPECT_TRUE(fs::exists(dir_ / "stats.json"));
    EXPECT_NE(r.out.find("frame 3/3"), std::string::npos);
    EXPECT_NE(r.out.find("Mrays/s"), std::string::npos);
    EXPECT_NE(r.out.find("reflection"), std::string::npos);
    EXPECT_EQ(outputs().size(), 2u);  // no temp files left behind
}

TEST_F(Cli, FramePatternWritesEveryFrame) {
    const RunResult r = runRaycache(
        "render --scene behind-0 --width 16 --height 16 --frames 3 --out " + (dir_ / "f_%04d.exr").string(), dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // Numbered like the progress lines: "frame 1/3" is f_0001.
    for (const char* name : {"f_0001.exr", "f_0002.exr", "f_0003.exr"}) EXPECT_TRUE(fs::exists(dir_ / name)) << name;
    EXPECT_FALSE(fs::exists(dir_ / "f_0000.exr"));
}

TEST_F(Cli, UsageAndInputErrorsExitTwoWithOneLineAndNoOutput) {
    const std::string png = (dir_ / "x.png").string();
    const std::array<std::string, 10> cases{
        "render --scene no-such-scene --out " + png,
        "render --scene room --width 0 --out " + png,
        "render --scene room --width abc --out " + png,
        "render --scene room --frames -3 --out " + png,
        "render --scene room --path sideways --out " + png,
        "render --scene room --accel foo --out " + png,
        "render --scene room --out " + (dir_ / "x.bmp").string(),
        "render --scene room --out /dev/null/missing-dir/x.png",  // a directory that cannot be created
        "render --scene " + (dir_ / "missing.json").string() + " --out " + png,
        "render --no-such-flag",
    };
    for (const std::string& args : cases) {
        const RunResult r = runRaycache(args, dir_);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << args << "\n" << r.err;
        EXPECT_TRUE(outputs().empty()) << args;
    }
}

TEST_F(Cli, TheDocumentedExampleSceneRenders) {
    const RunResult r = runRaycache(std::string("render --scene ") + RAYCACHE_SOURCE_DIR +
                                        "/examples/scenes/example.json --width 32 --height 24 --frames 2 --out " +
                                        (dir_ / "example.png").string(),
                                    dir_);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "example.png"));
}

TEST_F(Cli, CdctSceneRenders) {
    const fs::path scene = dir_ / "cdct.json";
    std::ofstream(scene) << R"({"objects": [{"shape": "sphere", "radius": 1,
        "material": {"kr": 0.5, "cache": {"technique": "cdct", "resolution": 16}}}]})";
    const RunResult r = runRaycache(
        "render --scene " + scene.string() + " --width 16 --height 16 --frames 2 --out " + (dir_ / "x.png").string(),
        dir_);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "x.png"));
    const RunResult flags = runRaycache(
        "render --scene behind-1 --technique cdct-parity --cache-res 16 --cdct-step 2 "
        "--cdct-epsilon 0.2 --cdct-max-depth 50 --width 16 --height 16 --frames 2 "
        "--out " +
            (dir_ / "y.png").string(),
        dir_);
    EXPECT_EQ(flags.exitCode, 0) << flags.err;
    EXPECT_TRUE(fs::exists(dir_ / "y.png"));
    const RunResult improved = runRaycache("render --scene behind-1 --technique cdct --cache-res 16 --cdct-tolerance 3 "
                                           "--width 16 --height 16 --frames 2 --out " +
                                               (dir_ / "z.png").string(),
                                           dir_);
    EXPECT_EQ(improved.exitCode, 0) << improved.err;
    EXPECT_NE(improved.out.find("pre-filled 1536"), std::string::npos) << improved.out;  // 6 * 16 * 16 texels
}

TEST_F(Cli, MalformedSceneFileNamesFileLineAndColumn) {
    const fs::path scene = dir_ / "bad.json";
    std::ofstream(scene) << "{\n  \"objects\": [\n    {\"shape\": \"sphere\", \"radius\": -1}\n  ]\n}\n";
    const RunResult r = runRaycache("render --scene " + scene.string() + " --out " + (dir_ / "x.png").string(), dir_);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("bad.json:3:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("/objects/0/radius"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

TEST_F(Cli, UnwritableOutputIsARuntimeErrorWithNoPartialFile) {
    // The target is an existing non-empty directory: rendering succeeds, the
    // final rename fails, and nothing may be left behind.
    fs::create_directories(dir_ / "taken.png" / "inside");
    const RunResult r = runRaycache(
        "render --scene behind-0 --width 8 --height 8 --frames 1 --out " + (dir_ / "taken.png").string(), dir_);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(outputs().size(), 1u);  // only the directory we made
}

TEST_F(Cli, RenderRejectsBadCachingOptionsWithOneLine) {
    const std::string png = (dir_ / "x.png").string();
    for (const std::string& args : {"render --scene behind-1 --technique bogus --out " + png,
                                    "render --scene behind-1 --cache-res 8 --out " + png,
                                    "render --scene behind-1 --technique cdct --cdct-step 0 --out " + png,
                                    "render --scene behind-1 --technique cdct --cdct-max-depth nan --out " + png,
                                    "render --scene behind-1 --cdct-step 0.1 --cdct-epsilon 0.2 --out " + png,
                                    "render --scene behind-1 --technique cdct --cdct-tolerance -1 --out " + png,
                                    "render --scene behind-1 --technique cdct --cdct-tolerance 1e9 --out " + png,
                                    "render --scene behind-1 --tile-balance bogus --out " + png,
                                    "render --scene behind-1 --cache-levels 9 --out " + png,
                                    "render --scene behind-1 --cache-levels 0 --out " + png,
                                    "render --scene behind-1 --cache-level-error 0 --out " + png,
                                    "render --scene behind-1 --cache-level-error nan --out " + png,
                                    "render --scene behind-1 --cdct-prefill-per-frame -1 --out " + png,
                                    "render --scene behind-1 --cdct-prefill-per-frame 1e3 --out " + png,
                                    "render --scene behind-1 --cache-budget -1 --out " + png,
                                    "render --scene behind-1 --cache-budget inf --out " + png,
                                    "render --scene behind-1 --cache-fill bogus --out " + png,
                                    "render --scene behind-1 --cache-fill --out " + png,
                                    "render --scene behind-1 --cache-res-from-view 3 --out " + png,
                                    "render --scene behind-1 --exposure nan --out " + png,
                                    "render --scene behind-1 --exposure 65 --out " + png,
                                    "render --scene behind-1 --spp 0 --out " + png,
                                    "render --scene behind-1 --spp 5000 --out " + png,
                                    "render --scene behind-1 --spp 4 --pipeline hybrid --gbuffer packets --out " + png,
                                    "render --scene behind-1 --spp 4 --pipeline render-cache --out " + png,
                                    // grid-32's 32 cubes need 12.5 KiB even at 4² faces.
                                    "render --scene grid-32 --cache-budget 0.001 --out " + png}) {
        const RunResult r = runRaycache(args, dir_);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << args << "\n" << r.err;
        EXPECT_TRUE(outputs().empty()) << args;
    }
}

// A name an option does not know is refused while the arguments are parsed,
// by every command that takes the option: one line naming the option and
// every name it takes, exit 2, nothing written.
TEST_F(Cli, BadNamesAreOneLineListingTheNames) {
    const std::string png = (dir_ / "x.png").string();
    const struct {
        std::string options, says;
    } cases[] = {
        {"--technique foo", "--technique: must be none, cct, cdct or cdct-parity (got 'foo')"},
        {"--pipeline foo", "--pipeline: must be ray, hybrid or render-cache (got 'foo')"},
        {"--accel foo", "--accel: must be embree or grids (got 'foo')"},
        {"--tile-balance foo", "--tile-balance: must be static, dynamic or claim (got 'foo')"},
        {"--path foo", "--path: must be static, orbit or pan (got 'foo')"},
        {"--path keyframes", "--path: must be static, orbit or pan (got 'keyframes')"},
        {"--cache-fill foo", "--cache-fill: must be off, exact or approximate (got 'foo')"},
        {"--cache-policy foo", "--cache-policy: must be auto or always (got 'foo')"},
        {"--gbuffer foo", "--gbuffer: must be auto, gl or packets (got 'foo')"},
        {"--rc-texture foo", "--rc-texture: must be refetch or reproject (got 'foo')"},
        {"--rc-reflections foo", "--rc-reflections: must be reshade or reproject (got 'foo')"},
        {"--technique CCT", "--technique: must be none, cct, cdct or cdct-parity (got 'CCT')"},
        {"--pipeline 1", "--pipeline: must be ray, hybrid or render-cache (got '1')"},
        {"--rc-texture 1", "--rc-texture: must be refetch or reproject (got '1')"},
        {"--view-transform foo", "--view-transform: must be standard, filmic, agx or khronos-pbr-neutral (got 'foo')"},
    };
    for (const auto& c : cases) {
        for (const std::string& command :
             {"render --scene behind-1 --out " + png, "cache-view --scene behind-1 --object main --out " + png,
              std::string("view --scene behind-1 --frames 1")}) {
            const std::string args = command + " " + c.options;
            // The view command's own --pipeline also takes auto (docs/viewer.md).
            std::string says = c.says;
            const std::string renderPipelines = "must be ray, hybrid or render-cache";
            if (command.rfind("view", 0) == 0 && says.rfind("--pipeline", 0) == 0)
                says.replace(says.find(renderPipelines), renderPipelines.size(),
                             "must be auto, ray, hybrid or render-cache");
            const RunResult r = runRaycache(args, dir_);
            EXPECT_EQ(r.exitCode, 2) << args;
            EXPECT_EQ(lineCount(r.err), 1) << args << "\n" << r.err;
            EXPECT_EQ(r.err.rfind("error: " + says, 0), 0u) << args << "\n" << r.err;
            EXPECT_TRUE(outputs().empty()) << args;
        }
    }
}

TEST_F(Cli, RenderNotesWhatTheCacheBudgetLowered) {
    const RunResult r = runRaycache("render --scene grid-8 --width 16 --height 16 --frames 1 --cache-budget 1", dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // 8 cubes of 512² (49.5 MiB) into 1 MiB.
    EXPECT_NE(r.out.find("note: cache budget 1.0 MiB: the cubes would take 49.5 MiB; lowered 8 of 8 cubes"),
              std::string::npos)
        << r.out;
}

// A mesh whose trouble spoils only an attribute loads; what was repaired is
// one "note:" line on stderr per file, however many objects use it.
TEST_F(Cli, RenderNotesARepairedMeshOnceOnStderr) {
    std::ofstream(dir_ / "mixed.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\n";
    std::ofstream(dir_ / "scene.json") << R"({"objects": [{"name": "a", "shape": "mesh", "file": "mixed.obj"},
                          {"name": "b", "shape": "mesh", "file": "mixed.obj", "transform": {"translate": [2, 0, 0]}}]})";
    const RunResult r =
        runRaycache("render --scene " + (dir_ / "scene.json").string() + " --width 16 --height 16", dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err, "note: " + (dir_ / "mixed.obj").string() + ": dropped 1 degenerate triangle of 2\n");
    EXPECT_EQ(r.out.find("note:"), std::string::npos) << r.out;
}

TEST_F(Cli, CacheViewWritesTheCubeCross) {
    const fs::path out = dir_ / "cross.png";
    const RunResult r = runRaycache(
        "cache-view --scene behind-1 --object main --width 32 --height 32 --frames 2 --cache-res 16 --out " +
            out.string(),
        dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(out));
    EXPECT_NE(r.out.find("frame 2/2"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("% invalid"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("MiB"), std::string::npos) << r.out;
    EXPECT_EQ(outputs().size(), 1u);  // no temp files left behind
}

TEST_F(Cli, CacheViewShowsTheDepthsOfAPrefilledCdctCube) {
    const fs::path out = dir_ / "depth.png";
    const RunResult r = runRaycache("cache-view --scene parallax --object left-mirror --technique cdct --show depth "
                                    "--width 32 --height 32 --frames 2 --cache-res 16 --out " +
                                        out.string(),
                                    dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("0.0% invalid"), std::string::npos) << r.out;
    // Pre-filled: no red (invalid) texel; the sky is blue, the floor and wall grey.
    const raycache::Image cross = raycache::loadImageFile(out);
    ASSERT_EQ(cross.width(), 64);
    int red = 0, blue = 0, grey = 0;
    for (const raycache::Rgb& p : cross.pixels()) {
        if (p.r > 0.9f && p.g < 0.1f) ++red;
        else if (p.b > 2.0f * p.r && p.b > 0.2f) ++blue;
        else if (p.r == p.g && p.g == p.b && p.r > 0.2f) ++grey;
    }
    EXPECT_EQ(red, 0);
    EXPECT_GT(blue, 0);
    EXPECT_GT(grey, 0);
}

TEST_F(Cli, CacheViewRejectsObjectsWithoutACubeBeforeRendering) {
    const std::string png = (dir_ / "cross.png").string();
    struct Case {
        std::string args;
        std::string says;  // part of the one error line
    };
    const Case cases[] = {
        {"cache-view --scene behind-2 --object nosuch --out " + png, "caching objects: main, behind0, behind1"},
        {"cache-view --scene behind-2 --object floor --out " + png, "neither reflective nor refractive"},
        {"cache-view --scene behind-2 --object main --technique none --out " + png, "technique is none"},
        {"cache-view --scene behind-2 --object main --out " + (dir_ / "cross.bmp").string(), ".bmp"},
        {"cache-view --scene behind-2 --object main --out /dev/null/missing-dir/x.png",
         "missing-dir"},
        {"cache-view --scene behind-2 --object main", "--out"},
        {"cache-view --scene behind-2 --object main --technique cct --show depth --out " + png, "keeps no depths"},
        {"cache-view --scene behind-2 --object main --show sideways --out " + png, "--show must be color or depth"},
    };
    for (const Case& c : cases) {
        const RunResult r = runRaycache(c.args, dir_);
        EXPECT_EQ(r.exitCode, 2) << c.args;
        EXPECT_EQ(lineCount(r.err), 1) << c.args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << c.args << "\n" << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_TRUE(r.out.find("frame 1/") == std::string::npos) << c.args;  // nothing was rendered
        EXPECT_TRUE(outputs().empty()) << c.args;
    }
}
