// What the raycache binary writes, opened and checked against an oracle, not
// only found on disk: the image is the last frame of the uncached render done
// in-process with the same options (the ground truth), the PNG is that image
// sRGB-encoded to 8 bits, the statistics JSON counts the rays that image
// needed; and the hybrid pipeline's fallback without OpenGL, exit code included.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "CliScratchTest.h"
#include "core/ColorSpace.h"
#include "core/Parallel.h"
#include "render/FramePipeline.h"
#include "scene/ImageLoader.h"
#include "session/PipelineFactory.h"
#include "session/RenderJob.h"
#include "trace/TraceScene.h"

namespace fs = std::filesystem;
using namespace raycache;

namespace {

using raycache::test::lineCount;
using raycache::test::RunResult;

class CliOutput : public raycache::test::CliScratchTest {
protected:
    CliOutput() : CliScratchTest("raycache-cli-output-") {}
};

// Frame `frame` of the job's camera path, rendered uncached in this process.
Image renderInProcess(const RenderJobOptions& options, int frame) {
    const RenderJob job = prepareRenderJob(options);
    const TraceScene tracer(job.scene);
    const Parallel parallel(job.settings.threads);
    const auto pipeline = makeFramePipeline(job.scene, tracer, job.settings, parallel);
    Image film;
    pipeline->render(job.path.cameraAt(job.scene.camera, frame), film);
    return film;
}

nlohmann::json readJson(const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

// grid-4 (four mirror spheres over a checkered floor, one light), uncached.
RenderJobOptions gridJob() {
    RenderJobOptions options;
    options.scene = "grid-4";
    options.width = 32;
    options.height = 24;
    options.frames = 3;
    options.technique = CacheTechnique::None;
    return options;
}
const std::string kGridArgs = "render --scene grid-4 --width 32 --height 24 --frames 3 --technique none";

}  // namespace

TEST_F(CliOutput, ExrIsTheLastFrameOfTheUncachedRenderBitForBit) {
    const RunResult r = run(kGridArgs + " --out " + (dir_ / "last.exr").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Image written = loadImageFile(dir_ / "last.exr");
    const Image expected = renderInProcess(gridJob(), 2);
    ASSERT_EQ(written.width(), 32);
    ASSERT_EQ(written.height(), 24);
    int differing = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) differing += !(written.at(x, y) == expected.at(x, y));
    EXPECT_EQ(differing, 0) << "pixels differing from frame 3 rendered in-process";
    // Not frame 1: the orbit moved the camera, so the two differ somewhere.
    const Image first = renderInProcess(gridJob(), 0);
    int movedPixels = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) movedPixels += !(first.at(x, y) == expected.at(x, y));
    EXPECT_GT(movedPixels, 0) << "frames 1 and 3 are the same image, so the test could not tell them apart";
}

TEST_F(CliOutput, PngIsTheSrgbEncodingOfTheLinearImage) {
    ASSERT_EQ(run(kGridArgs + " --out " + (dir_ / "last.png").string()).exitCode, 0);
    const Image png = loadImageFile(dir_ / "last.png");  // decoded back to linear
    const Image expected = renderInProcess(gridJob(), 2);
    ASSERT_EQ(png.width(), 32);
    ASSERT_EQ(png.height(), 24);
    // The sRGB transfer function (IEC 61966-2-1) rounds to the nearest of 255 steps.
    int off = 0;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 32; ++x) {
            const Rgb p = png.at(x, y), e = expected.at(x, y);
            for (const auto& [got, want] : {std::pair{p.r, e.r}, std::pair{p.g, e.g}, std::pair{p.b, e.b}}) {
                const double code = std::round(255.0 * std::min(1.0f, linearToSrgb(std::max(0.0f, want))));
                off += std::fabs(255.0 * linearToSrgb(got) - code) > 0.01;
            }
        }
    EXPECT_EQ(off, 0) << "channels whose 8-bit code is not the rounded sRGB encoding";
}

TEST_F(CliOutput, StatsJsonCountsTheRaysOfEveryFrame) {
    const fs::path stats = dir_ / "stats.json";
    const RunResult r = run(kGridArgs + " --max-depth 3 --stats " + stats.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json j = readJson(stats);
    EXPECT_EQ(j.at("scene"), "grid-4");
    EXPECT_EQ(j.at("width"), 32);
    EXPECT_EQ(j.at("height"), 24);
    EXPECT_EQ(j.at("max_depth"), 3);
    EXPECT_EQ(j.at("pipeline"), "ray");
    const nlohmann::json& frames = j.at("frames");
    ASSERT_EQ(frames.size(), 3u);
    std::uint64_t total = 0;
    for (std::size_t f = 0; f < frames.size(); ++f) {
        const nlohmann::json& rays = frames[f].at("rays");
        EXPECT_EQ(frames[f].at("frame"), static_cast<int>(f) + 1);  // frames count from 1, as "frame 1/N"
        EXPECT_EQ(rays.at("primary"), 32 * 24) << "one primary ray per pixel";
        // One light: at most one shadow ray per surface hit; depth 3 caps
        // reflections at two per pixel; grid-4 has no glass.
        EXPECT_GT(rays.at("shadow").get<std::uint64_t>(), 0u);
        EXPECT_LE(rays.at("shadow").get<std::uint64_t>(), 3u * 32 * 24);
        EXPECT_GT(rays.at("reflection").get<std::uint64_t>(), 0u);
        EXPECT_LE(rays.at("reflection").get<std::uint64_t>(), 2u * 32 * 24);
        EXPECT_EQ(rays.at("refraction"), 0);
        EXPECT_EQ(rays.at("total").get<std::uint64_t>(),
                  rays.at("primary").get<std::uint64_t>() + rays.at("shadow").get<std::uint64_t>() +
                      rays.at("reflection").get<std::uint64_t>() + rays.at("refraction").get<std::uint64_t>() +
                      rays.at("prefill").get<std::uint64_t>());
        EXPECT_FALSE(frames[f].contains("cache")) << "technique none keeps no cache";
        total += rays.at("total").get<std::uint64_t>();
    }
    EXPECT_EQ(j.at("summary").at("rays").at("total").get<std::uint64_t>(), total);
    const double median = j.at("summary").at("median_ms").get<double>();
    EXPECT_LE(j.at("summary").at("min_ms").get<double>(), median);
    EXPECT_LE(median, j.at("summary").at("max_ms").get<double>());
}

// --threads above the hardware threads is clamped (with a note); the JSON
// records the threads that ran and, apart, the number asked for.
TEST_F(CliOutput, StatsJsonRecordsTheThreadsUsedNotRequested) {
    const fs::path clamped = dir_ / "clamped.json", all = dir_ / "all.json";
    const RunResult r = run(kGridArgs + " --threads 1000 --stats " + clamped.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("note: --threads 1000 is more than the"), std::string::npos) << r.out;
    const nlohmann::json j = readJson(clamped);
    EXPECT_EQ(j.at("threads").get<int>(), Parallel::hardwareThreads());
    EXPECT_EQ(j.at("threads_requested").get<int>(), 1000);

    ASSERT_EQ(run(kGridArgs + " --stats " + all.string()).exitCode, 0);
    EXPECT_EQ(readJson(all).at("threads").get<int>(), Parallel::hardwareThreads()) << "0 means all";
    EXPECT_EQ(readJson(all).at("threads_requested").get<int>(), 0);

    ASSERT_EQ(run(kGridArgs + " --threads 1 --stats " + all.string()).exitCode, 0);
    EXPECT_EQ(readJson(all).at("threads").get<int>(), 1);
    EXPECT_EQ(readJson(all).at("threads_requested").get<int>(), 1);
}

// The counts, not the policy: under `always` the third frame reads what the
// first two stored (`auto` may stand this tiny image's cubes aside).
TEST_F(CliOutput, StatsJsonCacheCountsAddUpWithCct) {
    const fs::path stats = dir_ / "stats.json";
    const RunResult r = run(
        "render --scene behind-1 --width 32 --height 32 --frames 3 --technique cct --cache-res 32 "
        "--cache-policy always --stats " +
        stats.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json frames = readJson(stats).at("frames");
    ASSERT_EQ(frames.size(), 3u);
    for (const nlohmann::json& frame : frames) {
        const nlohmann::json& c = frame.at("cache");
        EXPECT_EQ(c.at("lookups").get<std::uint64_t>(), c.at("hits").get<std::uint64_t>() +
                                                            c.at("misses").get<std::uint64_t>() +
                                                            c.at("rejected").get<std::uint64_t>());
        // behind-1: the main mirror ball and the one behind it each have a cube.
        ASSERT_EQ(c.at("objects").size(), 2u);
        std::uint64_t objectLookups = 0;
        for (const nlohmann::json& o : c.at("objects")) {
            EXPECT_EQ(o.at("resolution"), 32) << "--cache-res 32";
            objectLookups += o.at("lookups").get<std::uint64_t>();
        }
        EXPECT_EQ(c.at("lookups").get<std::uint64_t>(), objectLookups);
    }
    EXPECT_EQ(frames[0].at("cache").at("hits"), 0) << "the cubes start empty";
    EXPECT_GT(frames[0].at("cache").at("stores").get<std::uint64_t>(), 0u);
    EXPECT_GT(frames[2].at("cache").at("hits").get<std::uint64_t>(), 0u) << "later frames reuse stored texels";
}

// Without any EGL vendor (glvnd pointed at a file that does not exist) the
// hybrid pipeline falls back to the packet G-buffer, says so in one line, exits
// 0, and writes exactly the ray pipeline's image (the packet G-buffer is
// bit-identical to it); --gbuffer gl then fails with one error line and exit 1.
TEST_F(CliOutput, HybridFallsBackToPacketsWithoutOpenGl) {
    const std::string noEgl = "__EGL_VENDOR_LIBRARY_FILENAMES=" + (dir_ / "no-such-egl-vendor.json").string() + " ";
    const std::string job = "render --scene behind-1 --width 32 --height 32 --frames 1 --technique none";
    const RunResult hybrid = raycache::test::runShell(
        noEgl + RAYCACHE_BINARY + " " + job + " --pipeline hybrid --out " + (dir_ / "hybrid.exr").string(),
        dir_ / "stderr.txt");
    ASSERT_EQ(hybrid.exitCode, 0) << hybrid.err;
    EXPECT_NE(hybrid.out.find("pipeline: hybrid, G-buffer by primary-ray packets (no OpenGL 4.5 core context"),
              std::string::npos)
        << hybrid.out;
    ASSERT_EQ(run(job + " --out " + (dir_ / "ray.exr").string()).exitCode, 0);
    const Image a = loadImageFile(dir_ / "hybrid.exr"), b = loadImageFile(dir_ / "ray.exr");
    ASSERT_EQ(a.width(), b.width());
    EXPECT_TRUE(a.pixels() == b.pixels()) << "hybrid (packets) and ray images differ";

    const RunResult gl = raycache::test::runShell(
        noEgl + RAYCACHE_BINARY + " " + job + " --pipeline hybrid --gbuffer gl --out " + (dir_ / "gl.exr").string(),
        dir_ / "stderr.txt");
    EXPECT_EQ(gl.exitCode, 1) << gl.err;
    EXPECT_EQ(lineCount(gl.err), 1) << gl.err;
    EXPECT_EQ(gl.err.rfind("error: no OpenGL 4.5 core context for the G-buffer: ", 0), 0u) << gl.err;
    EXPECT_FALSE(fs::exists(dir_ / "gl.exr"));
}
