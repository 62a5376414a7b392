// `raycache render --pipeline render-cache` as a user meets it: bad options
// are one error line and exit 2; a good run writes the Render Cache's
// statistics per frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/CliScratchTest.h"

namespace fs = std::filesystem;

namespace {

using raycache::test::lineCount;
using raycache::test::RunResult;

class RenderCacheCli : public raycache::test::CliScratchTest {
protected:
    RenderCacheCli() : CliScratchTest("raycache-rc-cli-") {}
};

}  // namespace

TEST_F(RenderCacheCli, BadOptionsAreOneErrorLineNamingTheOptionAndExit2) {
    const std::string base =
        "render --scene grid-1 --width 16 --height 16 --frames 1 --out " + (dir_ / "out.png").string() + " ";
    const struct {
        std::string args, option;
    } cases[] = {
        {"--pipeline render-cache --rc-alpha 1.5", "--rc-alpha"},
        {"--pipeline render-cache --rc-alpha -0.1", "--rc-alpha"},
        {"--pipeline render-cache --rc-alpha nan", "--rc-alpha"},
        {"--pipeline render-cache --rc-budget 0", "--rc-budget"},
        {"--pipeline render-cache --rc-budget -0.5", "--rc-budget"},
        {"--pipeline render-cache --rc-budget 2", "--rc-budget"},
        {"--pipeline render-cache --rc-max-age 0", "--rc-max-age"},
        {"--pipeline render-cache --rc-max-age 70000", "--rc-max-age"},
        {"--pipeline render-cache --rc-predict 1", "--rc-predict"},
        {"--pipeline render-cache --rc-target-ms -1", "--rc-target-ms"},
        {"--pipeline render-cache --rc-reflections bogus", "--rc-reflections"},
        {"--pipeline render-cache --rc-margin 0.6", "--rc-margin"},
        {"--pipeline render-cache --rc-depth-cull -0.1", "--rc-depth-cull"},
        {"--pipeline render-cache --rc-tile 0", "--rc-tile"},
        {"--pipeline render-cache --rc-reshade-every 0", "--rc-reshade-every"},
        {"--pipeline render-cache --rc-reshade-every 17", "--rc-reshade-every"},
        {"--pipeline bogus", "--pipeline"},
    };
    for (const auto& c : cases) {
        const RunResult r = run(base + c.args);
        EXPECT_EQ(r.exitCode, 2) << c.args << ": " << r.err;
        EXPECT_EQ(lineCount(r.err), 1) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.option), std::string::npos) << c.args << ": " << r.err;
        EXPECT_FALSE(fs::exists(dir_ / "out.png")) << c.args;
    }
}

TEST_F(RenderCacheCli, StatisticsJsonCarriesTheRenderCachesCountsPerFrame) {
    const fs::path stats = dir_ / "stats.json";
    const RunResult r =
        run("render --scene room --pipeline render-cache --frames 3 --width 32 --height 32 --threads 2 "
            "--out " +
            (dir_ / "f%d.png").string() + " --stats " + stats.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream in(stats);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("pipeline"), "render-cache");
    const nlohmann::json& frames = j.at("frames");
    ASSERT_EQ(frames.size(), 3u);
    for (std::size_t f = 0; f < frames.size(); ++f) {
        const nlohmann::json& rc = frames[f].at("render_cache");
        for (const char* key : {"reconstruction_ms", "sample_generation_ms"}) {
            ASSERT_TRUE(rc.at(key).is_number()) << key;
            EXPECT_GE(rc.at(key).get<double>(), 0.0) << key;
        }
        EXPECT_EQ(rc.at("pixels"), 1024);
        EXPECT_EQ(rc.at("refreshed_all"), f == 0) << "frame " << f;
        const std::int64_t fresh = rc.at("fresh"), holes = rc.at("holes");
        if (f == 0) {
            EXPECT_EQ(fresh, 1024);
            EXPECT_EQ(holes, 1024) << "nothing to reproject into the first frame";
        } else {
            // The default budget: 5 % of 1024 pixels, rounded; the orbit opens some holes.
            EXPECT_EQ(rc.at("budget"), 51);
            EXPECT_LE(fresh, 51);
            EXPECT_GE(holes, 0);
        }
        // The bytes reconstruction moves, counted (not measured), per pass
        // and per timed step, and over the step's time.
        const nlohmann::json& bytes = rc.at("counted_bytes");
        std::int64_t passes = 0;
        for (const char* pass : {"first_round", "copy", "holes", "request_maps", "fills"}) {
            ASSERT_TRUE(bytes.at(pass).is_number_integer()) << pass;
            EXPECT_GT(bytes.at(pass).get<std::int64_t>(), 0) << pass << ", frame " << f;
            passes += bytes.at(pass).get<std::int64_t>();
        }
        EXPECT_EQ(bytes.at("reproject").get<std::int64_t>(),
                  bytes.at("first_round").get<std::int64_t>() + bytes.at("copy").get<std::int64_t>());
        EXPECT_EQ(bytes.at("maps").get<std::int64_t>(),
                  bytes.at("holes").get<std::int64_t>() + bytes.at("request_maps").get<std::int64_t>());
        EXPECT_EQ(bytes.at("filter"), bytes.at("fills"));
        EXPECT_EQ(bytes.at("reconstruction").get<std::int64_t>(), passes);
        const nlohmann::json& rate = rc.at("counted_gb_per_s");
        for (const char* step : {"reproject", "maps", "filter", "reconstruction"}) {
            ASSERT_TRUE(rate.at(step).is_number()) << step;  // never null: 0 without time
            EXPECT_GE(rate.at(step).get<double>(), 0.0) << step;
        }
        const double ms = rc.at("reconstruction_ms");
        if (ms > 0.0) {
            const double expected = static_cast<double>(passes) / (ms * 1e6);
            EXPECT_NEAR(rate.at("reconstruction").get<double>(), expected, 1e-9 * expected);
        }
    }
    EXPECT_TRUE(fs::exists(dir_ / "f1.png"));
    EXPECT_TRUE(fs::exists(dir_ / "f3.png"));
}
