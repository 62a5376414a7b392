// `raycache diff` and `raycache bench` as a user meets them: printed metrics
// of known images, exit codes, one-line errors, and no partial output.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "TempDir.h"
#include "ShellRun.h"
#include "core/Image.h"
#include "render/ImageWriter.h"

namespace fs = std::filesystem;

namespace {

using raycache::test::lineCount;
using raycache::test::RunResult;

// Its stderr goes to a file beside `dir`, so that `dir` holds only what raycache wrote.
RunResult runRaycacheStderrBeside(const std::string& args, const fs::path& dir) {
    const fs::path errFile = dir.parent_path() / (dir.filename().string() + "-stderr.txt");
    RunResult result = raycache::test::runShell(std::string(RAYCACHE_BINARY) + " " + args, errFile);
    fs::remove(errFile);
    return result;
}

class DiffBenchCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = raycache::scratchPathForThisTest("raycache-diffbench-");
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        raycache::Image black(8, 8), white(8, 8), half(8, 8), other(9, 8);
        for (raycache::Rgb& p : white.pixels()) p = raycache::Rgb{1.0f};
        for (int x = 0; x < 8; ++x)
            for (int y = 0; y < 4; ++y) half.at(x, y) = raycache::Rgb{1.0f};
        raycache::writeImage(black, dir_ / "black.png");
        raycache::writeImage(white, dir_ / "white.png");
        raycache::writeImage(half, dir_ / "half.png");
        raycache::writeImage(other, dir_ / "other-size.png");
        inputs_ = fileCount();
    }
    void TearDown() override { fs::remove_all(dir_); }
    std::string path(const char* name) const { return (dir_ / name).string(); }
    std::size_t fileCount() const {
        return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
    }
    fs::path dir_;
    std::size_t inputs_ = 0;
};

}  // namespace

TEST_F(DiffBenchCli, DiffPrintsMetricsOfKnownImages) {
    // Black against half white: MSE 0.5 -> PSNR 10 log10(2) = 3.01 dB, MAE 0.5.
    const RunResult r = runRaycacheStderrBeside("diff " + path("black.png") + " " + path("half.png"), dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("MAE   0.500000"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("PSNR  3.01 dB"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("SSIM  "), std::string::npos) << r.out;

    // Identical: infinite PSNR, SSIM 1.
    const RunResult same = runRaycacheStderrBeside("diff " + path("white.png") + " " + path("white.png"), dir_);
    ASSERT_EQ(same.exitCode, 0) << same.err;
    EXPECT_NE(same.out.find("PSNR  inf (identical)"), std::string::npos) << same.out;
    EXPECT_NE(same.out.find("SSIM  1.00000"), std::string::npos) << same.out;

    // Black against white (constant): SSIM = C1 / (1 + C1) = 0.0001 / 1.0001.
    const RunResult bw = runRaycacheStderrBeside("diff " + path("black.png") + " " + path("white.png"), dir_);
    ASSERT_EQ(bw.exitCode, 0) << bw.err;
    EXPECT_NE(bw.out.find("PSNR  0.00 dB"), std::string::npos) << bw.out;
    EXPECT_NE(bw.out.find("SSIM  0.00010"), std::string::npos) << bw.out;
    EXPECT_EQ(fileCount(), inputs_);  // no heat map unless asked
}

TEST_F(DiffBenchCli, DiffWritesAHeatmap) {
    const RunResult r =
        runRaycacheStderrBeside("diff " + path("black.png") + " " + path("half.png") + " --heatmap " + path("map.png"), dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "map.png"));
    EXPECT_EQ(fileCount(), inputs_ + 1);  // no temporary file left
}

TEST_F(DiffBenchCli, DiffBadInputIsOneLineExitTwoAndNoHeatmap) {
    const std::string map = " --heatmap " + path("map.png");
    const std::array<std::string, 7> cases{
        "diff " + path("black.png") + " " + path("missing.png") + map,
        "diff " + path("black.png") + " " + path("other-size.png") + map,
        "diff " + path("black.png") + " " + path("white.png") + " --heatmap " + path("map.bmp"),
        "diff " + path("black.png") + " " + path("white.png") + " --heatmap " +
            "/dev/null/no-dir/m.png",  // cannot be created
        "diff " + path("black.png") + " " + path("white.png") + map + " --heatmap-max 0",
        "diff " + path("black.png") + map,
        "diff " + path("black.png") + " " + path("black.png") + " --no-such-flag",
    };
    for (const std::string& args : cases) {
        const RunResult r = runRaycacheStderrBeside(args, dir_);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << args << "\n" << r.err;
        EXPECT_EQ(fileCount(), inputs_) << args;
    }
}

TEST_F(DiffBenchCli, BenchListsAndRejectsBadOptionsBeforeRunning) {
    const RunResult list = runRaycacheStderrBeside("bench --list", dir_);
    ASSERT_EQ(list.exitCode, 0) << list.err;
    EXPECT_EQ(lineCount(list.out), 10);
    for (const char* name :
         {"table-5.1", "table-5.2", "table-5.3", "fill-rate", "quality", "parallax", "render-cache", "dynamic",
          "grids", "where-caching-pays"})
        EXPECT_NE(list.out.find(name), std::string::npos) << name;

    const std::string out = " --out " + (dir_ / "results").string();
    for (const std::string& args : {"bench no-such-experiment" + out, "bench table-5.1 --quick --full" + out,
                                    "bench" + out, "bench all --threads -1" + out,
                                    "bench fill-rate --cache-policy sometimes" + out}) {
        const RunResult r = runRaycacheStderrBeside(args, dir_);
        EXPECT_EQ(r.exitCode, 2) << args;
        EXPECT_EQ(lineCount(r.err), 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << args << "\n" << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "results")) << args;
    }
    const RunResult policy = runRaycacheStderrBeside("bench fill-rate --cache-policy sometimes" + out, dir_);
    EXPECT_EQ(policy.err.rfind("error: --cache-policy: must be auto or always (got 'sometimes')", 0), 0u) << policy.err;
}

TEST_F(DiffBenchCli, BenchRunsOneExperimentWithPlainProgressLines) {
    // Not a terminal: plain lines, no carriage returns or escape codes.
    const RunResult r = runRaycacheStderrBeside("bench fill-rate --tiny --threads 2 --out " + (dir_ / "results").string(), dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out.find('\r'), std::string::npos);
    EXPECT_EQ(r.out.find('\033'), std::string::npos);
    EXPECT_NE(r.out.find("[  0%] fill-rate: 128"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(dir_ / "results" / "fill-rate" / "results.json"));
    EXPECT_TRUE(fs::exists(dir_ / "results" / "fill-rate" / "invalid-texels.svg"));
    EXPECT_FALSE(fs::exists(dir_ / "results" / "report.md"));  // only `bench all` writes the report
}

TEST_F(DiffBenchCli, BenchCachePolicyAutoReachesOnlyTheExperimentsThatHonourIt) {
    const fs::path results = dir_ / "results";
    const RunResult r = runRaycacheStderrBeside(
        "bench parallax table-5.2 --tiny --threads 2 --cache-policy auto --out " + results.string(), dir_);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto policyOf = [&](const char* experiment) {
        std::ifstream in(results / experiment / "results.json");
        return nlohmann::json::parse(in).at("settings").at("cache_policy").get<std::string>();
    };
    EXPECT_EQ(policyOf("parallax"), "auto");
    EXPECT_EQ(policyOf("table-5.2"), "always");  // the documents' protocol
    // The terminal says which experiment did not take it, and only that one.
    const std::string note = "--cache-policy auto not applied";
    const std::size_t at = r.out.find(note);
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_EQ(r.out.find(note, at + 1), std::string::npos) << r.out;
    EXPECT_LT(r.out.find("Table 5.2"), at) << r.out;
}

TEST_F(DiffBenchCli, HelpForDiffAndBench) {
    for (const char* args : {"diff --help", "bench --help"}) {
        const RunResult r = runRaycacheStderrBeside(args, dir_);
        EXPECT_EQ(r.exitCode, 0) << args;
        EXPECT_NE(r.out.find("Usage"), std::string::npos) << args;
    }
}

TEST_F(DiffBenchCli, BenchResultsDirectoryThatIsAFileIsARuntimeError) {
    std::ofstream(dir_ / "taken") << "not a directory";
    const RunResult r = runRaycacheStderrBeside("bench fill-rate --tiny --out " + (dir_ / "taken").string(), dir_);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
}
