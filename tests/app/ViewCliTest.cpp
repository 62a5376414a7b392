// `raycache view` as a user meets it: a scripted run in a real X server
// (Xvfb, Mesa) whose window shows exactly the offline render of the same
// camera, and one-line errors for bad input or no display.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "CiRequirement.h"
#include "ShellRun.h"
#include "TempDir.h"
#include "core/ColorSpace.h"
#include "metrics/ImageMetrics.h"
#include "scene/ImageLoader.h"

namespace fs = std::filesystem;

namespace {

using raycache::test::lineCount;
using raycache::test::RunResult;

// Runs `command` (a shell command line) capturing stdout and stderr.
RunResult run(const std::string& command, const fs::path& dir) {
    return raycache::test::runShell(command, dir / "stderr.txt");
}

bool haveXvfbRun() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

// xvfb-run starts a private X server (-a: a free display number).
// In sanitizer builds, Mesa's GLX driver leaks ~240 bytes at exit from a
// library unloaded before LeakSanitizer runs, so the leak cannot be named in
// a suppression: leak checking is off for these runs only (address and UB
// checks stay on; the viewer's own code is leak-checked by viewer_tests).
// Two `xvfb-run -a` starting at once can pick the same display number:
// flock makes concurrent tests (ctest -j) take turns.
std::string underXvfb(const std::string& args) {
    const std::string lock = (fs::temp_directory_path() / "raycache-xvfb.lock").string();
    return "ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" flock " + lock +
           " xvfb-run -a -s '-screen 0 1280x1024x24' " + std::string(RAYCACHE_BINARY) + " " + args;
}

class ViewCli : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = raycache::scratchPathForThisTest("raycache-view-");
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

// The same scene, size, path frames, threads and caching for both commands.
const std::string kJob = "--scene room --width 320 --height 180 --frames 6 --threads 2 --technique cct";

}  // namespace

TEST_F(ViewCli, ScriptedRunShowsTheOfflineRenderOfTheSameCamera) {
    if (!haveXvfbRun()) {
        RAYCACHE_SKIP_OR_FAIL_IN_CI("xvfb-run is not installed (scripts/install-deps.sh installs xvfb)");
    }
    const fs::path shot = dir_ / "view.png", offline = dir_ / "offline.png";
    const RunResult view = run(underXvfb("view " + kJob + " --hide-ui --screenshot " + shot.string()), dir_);
    ASSERT_EQ(view.exitCode, 0) << view.err << view.out;
    EXPECT_NE(view.out.find("frame 6/6"), std::string::npos) << view.out;
    // The default pipeline is auto; playing the path is not moving the camera: full frames.
    EXPECT_NE(view.out.find("| auto: full frames"), std::string::npos) << view.out;
    EXPECT_EQ(view.out.find("| auto: Render Cache"), std::string::npos) << view.out;
    EXPECT_NE(view.out.find("screenshot " + shot.string() + " (320x180)"), std::string::npos) << view.out;
    const RunResult render =
        run(std::string(RAYCACHE_BINARY) + " render " + kJob + " --out " + offline.string(), dir_);
    ASSERT_EQ(render.exitCode, 0) << render.err;

    // The screenshot is read back from the window's framebuffer: it went
    // through the texture upload and the blit on Mesa's OpenGL.
    const raycache::Image shown = raycache::loadImageFile(shot);
    const raycache::Image reference = raycache::loadImageFile(offline);
    ASSERT_EQ(shown.width(), 320);
    ASSERT_EQ(shown.height(), 180);
    // The worker encodes with exactly the PNG writer's codes and the blit is
    // 1:1, so every 8-bit value must match (measured: identical, PSNR inf).
    int differing = 0;
    for (int y = 0; y < shown.height(); ++y)
        for (int x = 0; x < shown.width(); ++x) differing += !(shown.at(x, y) == reference.at(x, y));
    const double psnr = raycache::psnr(shown, reference);
    std::printf("view vs render: PSNR %.2f dB, %d of %d pixels differ\n", psnr, differing, 320 * 180);
    EXPECT_EQ(differing, 0);
    EXPECT_TRUE(std::isinf(psnr)) << psnr;
}

// `view --spp N` refines a still view, one sample layer a frame: a scripted
// run on a still path shows `raycache render --spp N`'s image once the plain
// frame and N layers have been shown.
TEST_F(ViewCli, ScriptedRunRefinesAStillViewToTheOfflineSampledImage) {
    if (!haveXvfbRun()) {
        RAYCACHE_SKIP_OR_FAIL_IN_CI("xvfb-run is not installed (scripts/install-deps.sh installs xvfb)");
    }
    const std::string job = "--scene glass --width 160 --height 120 --frames 5 --path static --threads 2 "
                            "--technique none --spp 4";
    const fs::path shot = dir_ / "view.png", offline = dir_ / "offline.png";
    const RunResult view = run(underXvfb("view " + job + " --hide-ui --screenshot " + shot.string()), dir_);
    ASSERT_EQ(view.exitCode, 0) << view.err << view.out;
    EXPECT_NE(view.out.find("| spp 0/4 (the plain frame)"), std::string::npos) << view.out;
    EXPECT_NE(view.out.find("| spp 4/4"), std::string::npos) << view.out;
    const RunResult render = run(std::string(RAYCACHE_BINARY) + " render " + job + " --out " + offline.string(), dir_);
    ASSERT_EQ(render.exitCode, 0) << render.err;
    const raycache::Image shown = raycache::loadImageFile(shot);
    const raycache::Image reference = raycache::loadImageFile(offline);
    ASSERT_EQ(shown.width(), reference.width());
    ASSERT_EQ(shown.height(), reference.height());
    int differing = 0;
    for (int y = 0; y < shown.height(); ++y)
        for (int x = 0; x < shown.width(); ++x) differing += !(shown.at(x, y) == reference.at(x, y));
    EXPECT_EQ(differing, 0);
}

// The Render Cache in a scripted run is synchronous unless asked: the
// window shows `raycache render`'s frame. Asked for async, it runs, saying
// what it merged and how fast its tracer traced.
TEST_F(ViewCli, ScriptedRenderCacheRunsAreSyncUnlessAskedAndAsyncWhenAsked) {
    if (!haveXvfbRun()) {
        RAYCACHE_SKIP_OR_FAIL_IN_CI("xvfb-run is not installed (scripts/install-deps.sh installs xvfb)");
    }
    const std::string job = "--scene room --width 160 --height 96 --frames 4 --threads 2 --pipeline render-cache";
    const fs::path shot = dir_ / "view.png", offline = dir_ / "offline.png";
    const RunResult view = run(underXvfb("view " + job + " --hide-ui --screenshot " + shot.string()), dir_);
    ASSERT_EQ(view.exitCode, 0) << view.err << view.out;
    EXPECT_EQ(view.out.find("async"), std::string::npos) << view.out;
    const RunResult render = run(std::string(RAYCACHE_BINARY) + " render " + job + " --out " + offline.string(), dir_);
    ASSERT_EQ(render.exitCode, 0) << render.err;
    const raycache::Image shown = raycache::loadImageFile(shot);
    const raycache::Image reference = raycache::loadImageFile(offline);
    int differing = 0;
    for (int y = 0; y < shown.height(); ++y)
        for (int x = 0; x < shown.width(); ++x) differing += !(shown.at(x, y) == reference.at(x, y));
    EXPECT_EQ(differing, 0);

    const RunResult async =
        run(underXvfb("view " + job + " --hide-ui --render-cache-display async --render-cache-trace-threads 1"), dir_);
    ASSERT_EQ(async.exitCode, 0) << async.err << async.out;
    EXPECT_NE(async.out.find("frame 4/4"), std::string::npos) << async.out;
    EXPECT_NE(async.out.find("| async: merged "), std::string::npos) << async.out;
    EXPECT_NE(async.out.find("trace Msamples/s"), std::string::npos) << async.out;
}

TEST_F(ViewCli, TheScreenshotIsTheWindowPanelIncluded) {
    if (!haveXvfbRun()) {
        RAYCACHE_SKIP_OR_FAIL_IN_CI("xvfb-run is not installed (scripts/install-deps.sh installs xvfb)");
    }
    const fs::path withPanel = dir_ / "panel.png", withoutPanel = dir_ / "frame.png";
    ASSERT_EQ(run(underXvfb("view " + kJob + " --screenshot " + withPanel.string()), dir_).exitCode, 0);
    ASSERT_EQ(run(underXvfb("view " + kJob + " --hide-ui --screenshot " + withoutPanel.string()), dir_).exitCode, 0);
    // The panel covers much of a 320x180 window: far from the bare frame.
    EXPECT_LT(raycache::psnr(raycache::loadImageFile(withPanel), raycache::loadImageFile(withoutPanel)), 25.0);
}

TEST_F(ViewCli, LevelOverlayTintsEachPixelByWhatTheCacheDidForIt) {
    if (!haveXvfbRun()) {
        RAYCACHE_SKIP_OR_FAIL_IN_CI("xvfb-run is not installed (scripts/install-deps.sh installs xvfb)");
    }
    const fs::path plain = dir_ / "plain.png", tinted = dir_ / "levels.png";
    ASSERT_EQ(run(underXvfb("view " + kJob + " --hide-ui --screenshot " + plain.string()), dir_).exitCode, 0);
    const RunResult view =
        run(underXvfb("view " + kJob + " --hide-ui --level-overlay --screenshot " + tinted.string()), dir_);
    ASSERT_EQ(view.exitCode, 0) << view.err << view.out;
    const raycache::Image a = raycache::loadImageFile(plain), b = raycache::loadImageFile(tinted);
    ASSERT_EQ(a.width(), b.width());
    ASSERT_EQ(a.height(), b.height());
    // The record never changes the frame, so each shown pixel is the plain
    // one blended (160 of 256) with grey (no caching object), red (traced)
    // or green (level 0): room's one mirror, single-level cubes.
    const std::array<std::array<int, 3>, 3> targets = {{{128, 128, 128}, {255, 0, 0}, {0, 255, 0}}};
    std::array<int, 4> pixels{};  // grey, red, green, anything else
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const raycache::Rgb p = a.at(x, y), q = b.at(x, y);
            const std::array<int, 3> under = {raycache::linearToSrgb8(p.r), raycache::linearToSrgb8(p.g),
                                              raycache::linearToSrgb8(p.b)};
            const std::array<int, 3> shown = {raycache::linearToSrgb8(q.r), raycache::linearToSrgb8(q.g),
                                              raycache::linearToSrgb8(q.b)};
            std::size_t kind = 0;
            for (; kind < targets.size(); ++kind) {
                bool same = true;
                for (std::size_t c = 0; c < 3; ++c)
                    same = same && shown[c] == ((under[c] * 96 + targets[kind][c] * 160) >> 8);
                if (same) break;
            }
            ++pixels[kind];
        }
    std::printf("level overlay: %d grey, %d red, %d green, %d other\n", pixels[0], pixels[1], pixels[2], pixels[3]);
    EXPECT_EQ(pixels[3], 0);
    EXPECT_GT(pixels[0], pixels[1] + pixels[2]);  // most of room is floor and diffuse objects
    EXPECT_GT(pixels[1] + pixels[2], 0);          // the mirror ball asked its cube
}

TEST_F(ViewCli, BadInputIsOneLineAndExitTwoWithoutAWindow) {
    // No X server here: input is checked before a window is opened.
    for (const std::string& args :
         {std::string("view --scene no-such-scene --frames 2"), std::string("view no-such-file.json"),
          std::string("view --scene room --frames 2 --screenshot ") + (dir_ / "shot.bmp").string(),
          std::string("view --scene room --frames 2 --screenshot ") + (dir_ / "missing-dir" / "s.png").string(),
          std::string("view --scene room --moving-scale 0"), std::string("view --scene room --max-depth 0"),
          std::string("view --scene room --render-cache-display fast"),
          std::string("view --scene room --render-cache-trace-threads -1"),
          std::string("view --scene room --render-cache-display-threads -1"),
          std::string("view --scene room --render-cache-request-frames -1"),
          std::string("view --scene room --pipeline fastest"), std::string("view --scene room --target-fps 0"),
          std::string("view --scene room --spp 4 --pipeline render-cache"),
          std::string("view --scene room --spp 4 --pipeline hybrid"), std::string("view --scene room --spp 0")}) {
        const RunResult r = run("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(RAYCACHE_BINARY) + " " + args, dir_);
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.err;
        EXPECT_EQ(lineCount(r.err), 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    }
    EXPECT_FALSE(fs::exists(dir_ / "shot.bmp"));
}

TEST_F(ViewCli, NoDisplayIsOneLineAndExitOne) {
    const RunResult r = run("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(RAYCACHE_BINARY) +
                                " view --scene room --frames 1 --screenshot " + (dir_ / "s.png").string(),
                            dir_);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("error: cannot open a window"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "s.png"));
}

TEST_F(ViewCli, HelpListsTheViewerOptions) {
    const RunResult r = run(std::string(RAYCACHE_BINARY) + " view --help", dir_);
    EXPECT_EQ(r.exitCode, 0);
    for (const char* option :
         {"--screenshot", "--frames", "--hide-ui", "--technique", "--moving-scale", "--level-overlay",
          "--render-cache-display", "--render-cache-trace-threads", "--render-cache-display-threads",
          "--render-cache-request-frames", "--pipeline", "auto", "--target-fps"})
        EXPECT_NE(r.out.find(option), std::string::npos) << option;
}
