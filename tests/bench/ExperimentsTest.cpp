// Every experiment at tiny size, through the bench command as a user runs
// it: well-formed results.json (parsed back, finite numbers, the expected
// keys), Markdown tables, SVG plots, images, and a report whose links all
// resolve. Tiny numbers mean nothing; only the shape and invariants are checked.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "TextPattern.h"
#include "XmlCheck.h"
#include "app/BenchCommand.h"
#include "bench/ExperimentRegistry.h"
#include "bench/SpeedupInterval.h"

namespace fs = std::filesystem;
using namespace raycache;

namespace {

std::string readFile(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Every number in the document is finite (JSON cannot hold NaN/inf; nlohmann
// writes them as null, which the bench only does on purpose via finiteOrNull).
void expectFiniteNumbers(const nlohmann::json& j, const std::string& where, int& count) {
    if (j.is_number()) {
        ++count;
        EXPECT_TRUE(std::isfinite(j.get<double>())) << where;
    } else if (j.is_object()) {
        for (auto it = j.begin(); it != j.end(); ++it) expectFiniteNumbers(it.value(), where + "/" + it.key(), count);
    } else if (j.is_array()) {
        for (std::size_t i = 0; i < j.size(); ++i) expectFiniteNumbers(j[i], where + "/" + std::to_string(i), count);
    }
}

// Each Markdown table has a separator line and every row has as many cells as its header.
int checkMarkdownTables(const std::string& md, const std::string& file) {
    std::istringstream in(md);
    std::string line;
    int tables = 0, headerCells = -1;
    std::string previous;
    const auto cells = [](const std::string& l) {
        int n = 0;
        for (std::size_t i = 0; i < l.size(); ++i)
            if (l[i] == '|' && (i == 0 || l[i - 1] != '\\')) ++n;
        return n - 1;
    };
    while (std::getline(in, line)) {
        if (line.rfind("| ---", 0) == 0) {
            ++tables;
            headerCells = cells(previous);
            EXPECT_EQ(cells(line), headerCells) << file << ": " << line;
        } else if (line.rfind("|", 0) == 0 && headerCells > 0 && previous.rfind("|", 0) == 0) {
            EXPECT_EQ(cells(line), headerCells) << file << ": " << line;
        } else if (line.rfind("|", 0) != 0) {
            headerCells = -1;
        }
        previous = line;
    }
    return tables;
}

class Experiments : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        // One directory per process: ctest runs the test cases as parallel processes.
        dir_ = fs::temp_directory_path() / ("raycache-bench-tiny-" + std::to_string(getpid()));
        fs::remove_all(dir_);
        BenchCommandOptions options;
        options.experiments = {"all"};
        options.tiny = true;
        options.threads = 2;
        options.outDir = dir_.string();
        std::ostringstream log;
        runBenchCommand(options, log);
        log_ = log.str();
    }
    static void TearDownTestSuite() { fs::remove_all(dir_); }

    static nlohmann::json results(const std::string& name) {
        return nlohmann::json::parse(readFile(dir_ / name / "results.json"));
    }

    static fs::path dir_;
    static std::string log_;
};

fs::path Experiments::dir_;
std::string Experiments::log_;

}  // namespace

TEST_F(Experiments, EveryExperimentWritesWellFormedJsonMarkdownAndSvg) {
    for (const auto& e : allExperiments()) {
        const fs::path d = dir_ / e->name();
        SCOPED_TRACE(e->name());
        ASSERT_TRUE(fs::exists(d / "results.json"));
        const nlohmann::json j = results(e->name());
        EXPECT_EQ(j.at("experiment"), e->name());
        EXPECT_EQ(j.at("size"), "tiny");
        EXPECT_FALSE(j.at("environment").at("cpu_model").get<std::string>().empty());
        // The same "version" object as `raycache render --stats` (bench/BuildInfo).
        for (const char* key : {"raycache", "git_commit", "build_type", "compiler", "embree", "embree_instructions",
                                "tbb", "assimp", "openexr", "lanes"})
            EXPECT_FALSE(j.at("environment").at("version").at(key).get<std::string>().empty()) << key;
        EXPECT_EQ(j.at("environment").at("worker_threads"), 2);
        int numbers = 0;
        expectFiniteNumbers(j, e->name(), numbers);
        EXPECT_GT(numbers, 10);

        const std::string md = readFile(d / "results.md");
        EXPECT_GE(checkMarkdownTables(md, e->name()), 1);
        int plots = 0;
        for (const auto& f : fs::directory_iterator(d)) {
            if (f.path().extension() != ".svg") continue;
            ++plots;
            const std::string svg = readFile(f.path());
            EXPECT_EQ(raycache::test::xmlProblem(svg), "") << f.path();
            EXPECT_GE(raycache::test::countOccurrences(svg, "class=\"series\""), 1) << f.path();
            EXPECT_NE(md.find("(" + f.path().filename().string() + ")"), std::string::npos)
                << "results.md links " << f.path().filename();
        }
        EXPECT_GE(plots, 1);
        EXPECT_NE(log_.find(e->title()), std::string::npos);
    }
}

TEST_F(Experiments, CachedExperimentsCacheEveryFrameByDefault) {
    // bench's default --cache-policy is always, so the reported tables stay comparable.
    for (const char* name : {"table-5.1", "table-5.2", "table-5.3", "fill-rate", "quality", "parallax", "dynamic"}) {
        SCOPED_TRACE(name);
        EXPECT_EQ(results(name).at("settings").at("cache_policy"), "always");
    }
    EXPECT_EQ(log_.find("not applied"), std::string::npos) << log_;
}

TEST_F(Experiments, TimingTablesRecordEveryFrameAndSayWhatIsMissing) {
    for (const char* name : {"table-5.1", "table-5.2", "table-5.3"}) {
        SCOPED_TRACE(name);
        const nlohmann::json j = results(name);
        const int timed = j.at("settings").at("timed_frames");
        const int moving = j.at("settings").at("moving_frames");
        ASSERT_FALSE(j.at("rows").empty());
        for (const auto& row : j.at("rows")) {
            for (const auto& [key, v] : row.at("variants").items()) {
                if (!v.at("available").get<bool>()) {
                    EXPECT_FALSE(v.at("unavailable_reason").get<std::string>().empty());
                    continue;
                }
                const auto& frames = v.at("still").at("frame_ms");
                ASSERT_EQ(static_cast<int>(frames.size()), timed) << key;
                for (const auto& ms : frames) EXPECT_GT(ms.get<double>(), 0.0);
                EXPECT_LE(v.at("still").at("min_ms").get<double>(), v.at("still").at("median_ms").get<double>());
                if (moving > 0) {
                    EXPECT_EQ(static_cast<int>(v.at("moving").at("frame_ms_per_round").at(0).size()), moving);
                }
            }
        }
    }
    // Table 5.1 is measured in the hybrid pipeline, as the documents did.
    EXPECT_EQ(results("table-5.1").at("settings").at("pipeline"), "hybrid");
    // Table 5.3 measures the improved CDCT beside the parity rows.
    const nlohmann::json t53 = results("table-5.3");
    EXPECT_TRUE(t53.at("rows").at(0).at("variants").at("cdct-improved").at("available").get<bool>());
    EXPECT_EQ(t53.at("rows").at(0).at("variants").at("cdct-0.02/0.002").at("cdct").at("step"), 0.02f);
    // The documents' figures sit beside ours.
    EXPECT_DOUBLE_EQ(t53.at("rows").at(1).at("variants").at("cct").at("documents_fps").get<double>(), 68.2);
}

TEST_F(Experiments, TimingTablesReportSpeedupsWithTheirIntervalsAndStopReasons) {
    for (const char* name : {"table-5.1", "table-5.2", "table-5.3"}) {
        SCOPED_TRACE(name);
        const nlohmann::json j = results(name);
        const int timed = j.at("settings").at("timed_frames");
        // Tiny runs a fixed count: fewer rounds than an interval needs, stopped by the round cap.
        EXPECT_EQ(j.at("settings").at("max_timed_frames").get<int>(), timed);
        EXPECT_FALSE(j.at("load_average").at("before").get<std::string>().empty());
        EXPECT_FALSE(j.at("load_average").at("after").get<std::string>().empty());
        // Linux has /proc/stat: others' share of the CPU time is known, a fraction.
        ASSERT_TRUE(j.at("others_cpu_share").is_number());
        EXPECT_GE(j.at("others_cpu_share").get<double>(), 0.0);
        EXPECT_LE(j.at("others_cpu_share").get<double>(), 1.0);
        for (const auto& row : j.at("rows")) {
            EXPECT_EQ(row.at("still_timed_rounds").get<int>(), timed);
            EXPECT_EQ(row.at("still_stop_reason"), "round cap");
            const auto& baseline = row.at("variants").at("standard").at("still").at("frame_ms");
            for (const auto& [key, v] : row.at("variants").items()) {
                if (!v.at("available").get<bool>()) continue;
                const nlohmann::json& s = v.at("still").at("speedup_vs_standard");
                // The recorded speed-up is what the recorded frames give.
                const SpeedupInterval expected = bootstrapSpeedup(
                    baseline.get<std::vector<double>>(), v.at("still").at("frame_ms").get<std::vector<double>>());
                EXPECT_NEAR(s.at("speedup").get<double>(), expected.speedup, 1e-9) << key;
                EXPECT_TRUE(s.at("ci95_low").is_null()) << key;  // fewer than 4 pairs: no interval
                EXPECT_FALSE(s.at("no_measurable_difference").get<bool>()) << key;
            }
        }
        EXPECT_NE(readFile(dir_ / name / "results.md").find("Timed rounds (still camera): "), std::string::npos);
    }
    EXPECT_NE(log_.find("(no interval: fewer than 4 timed pairs)"), std::string::npos);
    EXPECT_NE(log_.find("load average "), std::string::npos);
    EXPECT_NE(log_.find("other processes used "), std::string::npos);
}

TEST_F(Experiments, FillRateStartsEmptyAndNeverLosesTexels) {
    const nlohmann::json j = results("fill-rate");
    ASSERT_EQ(j.at("series").size(), 3u);
    for (const auto& s : j.at("series")) {
        const auto& before = s.at("invalid_percent_before_frame");
        ASSERT_EQ(before.size(), 10u);
        EXPECT_DOUBLE_EQ(before.at(0).get<double>(), 100.0);
        double previous = 100.0;
        for (const auto& v : before) {
            EXPECT_LE(v.get<double>(), previous);
            previous = v.get<double>();
        }
        EXPECT_LE(s.at("invalid_percent_after_last_frame").get<double>(), previous);
    }
    // Multi-resolution cubes along the same path: every lookup of the first
    // frame is traced (the cubes start empty), and every share is a percentage.
    ASSERT_EQ(j.at("multi_resolution").size(), 2u);
    for (const auto& m : j.at("multi_resolution")) {
        EXPECT_EQ(m.at("levels").get<int>(), 4);
        const auto& traced = m.at("traced_percent");
        ASSERT_EQ(traced.size(), 10u);
        EXPECT_DOUBLE_EQ(traced.at(0).get<double>(), 100.0);
        for (const auto& t : traced) {
            EXPECT_GE(t.get<double>(), 0.0);
            EXPECT_LE(t.get<double>(), 100.0);
        }
    }
    // The cube sized from the view never exceeds the faces asked for; the
    // visible-surface fill's shares are percentages, from 100 in frame 1.
    const auto& fromView = j.at("from_view");
    for (const auto& size : fromView.at("faces_after_frame")) {
        EXPECT_GE(size.get<int>(), 16);
        EXPECT_LE(size.get<int>(), fromView.at("asked_faces").get<int>());
    }
    const auto& filled = j.at("visible_fill").at("traced_percent");
    ASSERT_EQ(filled.size(), 10u);
    EXPECT_DOUBLE_EQ(filled.at(0).get<double>(), 100.0);
    for (const auto& t : filled) {
        EXPECT_GE(t.get<double>(), 0.0);
        EXPECT_LE(t.get<double>(), 100.0);
    }
}

TEST_F(Experiments, QualityAndParallaxMetricsAreInRange) {
    const nlohmann::json q = results("quality");
    ASSERT_EQ(q.at("rows").size(), 2u * 6u * 3u);  // views x fill protocols x resolutions
    int multiResolutionRows = 0;
    for (const auto& row : q.at("rows")) {
        // The third and fourth fill protocols measure multi-resolution cubes,
        // the fifth a cube sized from the view, the sixth the visible-surface fill.
        const bool multiResolution = row.at("fill") == "orbit-levels" || row.at("fill") == "orbit-levels-wide";
        EXPECT_EQ(row.at("cube_levels").get<int>(), multiResolution ? 4 : 1) << row.at("fill");
        EXPECT_EQ(row.at("resolution_from_view").get<bool>(), row.at("fill") == "orbit-view") << row.at("fill");
        EXPECT_EQ(row.at("visible_fill").get<bool>(), row.at("fill") == "orbit-visible-fill") << row.at("fill");
        multiResolutionRows += multiResolution ? 1 : 0;
        const auto& m = row.at("metrics");
        EXPECT_GE(m.at("mae").get<double>(), 0.0);
        EXPECT_LE(m.at("mae").get<double>(), 1.0);
        EXPECT_LE(m.at("ssim").get<double>(), 1.0);
        EXPECT_GE(m.at("ssim").get<double>(), -1.0);
        EXPECT_TRUE(m.at("psnr_db").is_null() || m.at("psnr_db").get<double>() > 0.0);
        for (const char* image : {"image", "heatmap", "heatmap_x4"})
            EXPECT_TRUE(fs::exists(dir_ / "quality" / row.at(image).get<std::string>())) << row.at(image);
    }
    EXPECT_EQ(multiResolutionRows, 2 * 2 * 3);
    const nlohmann::json p = results("parallax");
    ASSERT_GE(p.at("variants").size(), 2u);
    for (const auto& v : p.at("variants")) EXPECT_EQ(v.at("frames").size(), p.at("settings").at("frames"));
}

TEST_F(Experiments, DynamicPlaysEveryAnimatedSceneAndFindsNoStaleTexel) {
    const nlohmann::json j = results("dynamic");
    const int frames = j.at("settings").at("frames");
    ASSERT_EQ(j.at("series").size(), 4u);
    for (const auto& s : j.at("series")) {
        EXPECT_EQ(s.at("uncached_ms").size(), static_cast<std::size_t>(frames)) << s.at("scene");
        EXPECT_EQ(s.at("cct_ms").size(), static_cast<std::size_t>(frames)) << s.at("scene");
        for (const char* protocol : {"as_timed", "coarse"}) {
            const auto& oracle = s.at("oracle").at(protocol);
            EXPECT_GT(oracle.at("checked").get<int>(), 0) << s.at("scene") << " " << protocol;
            EXPECT_EQ(oracle.at("stale").get<int>(), 0) << s.at("scene") << " " << protocol;
            EXPECT_EQ(oracle.at("kept").get<int>() + oracle.at("dropped").get<int>(), oracle.at("checked").get<int>());
        }
    }
}

TEST_F(Experiments, RenderCacheSplitsFrameTimeAndItsFirstFrameIsTheFullRender) {
    const nlohmann::json j = results("render-cache");
    const int frames = j.at("settings").at("frames");
    EXPECT_EQ(frames, 4);
    EXPECT_EQ(j.at("settings").at("skipped_frames"), 1);
    EXPECT_DOUBLE_EQ(j.at("documents").at("rows").at(0).at("fps").get<double>(), 123.0);
    ASSERT_EQ(j.at("runs").size(), 3u);  // room, behind-32, glass at 48²
    for (const auto& run : j.at("runs")) {
        const std::string scene = run.at("scene");
        SCOPED_TRACE(scene);
        const int side = run.at("width");
        EXPECT_EQ(side, 48);
        const std::int64_t pixels = static_cast<std::int64_t>(side) * side;
        const auto fullMs = run.at("full").at("frame_ms").get<std::vector<double>>();
        ASSERT_EQ(static_cast<int>(fullMs.size()), frames);
        const auto mirrorPixels = run.at("mirror_pixels").get<std::vector<std::int64_t>>();
        ASSERT_EQ(static_cast<int>(mirrorPixels.size()), frames);
        for (std::int64_t m : mirrorPixels) {
            EXPECT_GT(m, 0);  // every scene shows a mirror or glass
            EXPECT_LT(m, pixels);
        }
        ASSERT_EQ(run.at("variants").size(), 2u);
        std::int64_t reshadedLater = 0;
        for (const char* key : {"reproject", "reshade"}) {
            SCOPED_TRACE(key);
            const nlohmann::json& v = run.at("variants").at(key);
            const nlohmann::json& f = v.at("frames");
            ASSERT_EQ(static_cast<int>(f.size()), frames);
            // Frame 1 has no samples to reproject: it traces every pixel, as the
            // full render does, and its image is the full render's exactly.
            const nlohmann::json& first = f.at(0);
            EXPECT_TRUE(first.at("refreshed_all").get<bool>());
            EXPECT_EQ(first.at("fresh").get<std::int64_t>(), pixels);
            EXPECT_DOUBLE_EQ(first.at("fresh_share").get<double>(), 1.0);
            EXPECT_EQ(first.at("holes").get<std::int64_t>(), pixels);
            EXPECT_TRUE(first.at("psnr_db").is_null());  // identical: infinite PSNR
            EXPECT_TRUE(first.at("mirror_psnr_db").is_null());
            EXPECT_DOUBLE_EQ(first.at("mae").get<double>(), 0.0);
            EXPECT_DOUBLE_EQ(first.at("ssim").get<double>(), 1.0);
            std::vector<double> laterMs;
            for (std::size_t k = 0; k < f.size(); ++k) {
                const nlohmann::json& x = f.at(k);
                EXPECT_EQ(x.at("frame").get<int>(), static_cast<int>(k) + 1);
                EXPECT_EQ(x.at("pixels").get<std::int64_t>(), pixels);
                const double ms = x.at("ms");
                EXPECT_GT(ms, 0.0);
                EXPECT_NEAR(x.at("reconstruction_ms").get<double>(),
                            x.at("reproject_ms").get<double>() + x.at("maps_ms").get<double>() +
                                x.at("filter_ms").get<double>(),
                            1e-9);
                EXPECT_NEAR(x.at("sample_generation_ms").get<double>(),
                            x.at("trace_ms").get<double>() + x.at("reshade_ms").get<double>(), 1e-9);
                // Reconstruction's counted bytes, and those over its time.
                const std::int64_t bytes = x.at("counted_bytes").at("reconstruction");
                EXPECT_GT(bytes, 0);
                EXPECT_EQ(bytes, x.at("counted_bytes").at("reproject").get<std::int64_t>() +
                                     x.at("counted_bytes").at("maps").get<std::int64_t>() +
                                     x.at("counted_bytes").at("filter").get<std::int64_t>());
                EXPECT_GE(x.at("counted_gb_per_s").at("reconstruction").get<double>(), 0.0);
                // The parts are timed inside the frame the whole is timed around.
                EXPECT_LE(x.at("reconstruction_ms").get<double>() + x.at("sample_generation_ms").get<double>(),
                          ms + 1e-6);
                EXPECT_GE(x.at("fresh_share").get<double>(), 0.0);
                EXPECT_LE(x.at("fresh_share").get<double>(), 1.0);
                EXPECT_LE(x.at("mirror_pixels").get<std::int64_t>(), pixels);
                EXPECT_LE(x.at("ssim").get<double>(), 1.0);
                EXPECT_TRUE(x.at("psnr_db").is_null() || x.at("psnr_db").get<double>() > 0.0);
                if (std::string(key) == "reproject") {
                    EXPECT_EQ(x.at("reshaded").get<std::int64_t>(), 0);
                }
                if (k == 0) continue;
                laterMs.push_back(ms);
                // A small camera step: the budget, 5 % of the pixels, is all a frame traces.
                EXPECT_FALSE(x.at("refreshed_all").get<bool>());
                EXPECT_EQ(x.at("budget").get<std::int64_t>(), std::lround(0.05 * static_cast<double>(pixels)));
                EXPECT_LE(x.at("fresh").get<std::int64_t>() + x.at("predicted").get<std::int64_t>(),
                          x.at("budget").get<std::int64_t>());
                EXPECT_LT(x.at("fresh_share").get<double>(), 0.1);
                EXPECT_GT(x.at("reprojected").get<std::int64_t>(), pixels / 2);
                if (std::string(key) == "reshade") reshadedLater += x.at("reshaded").get<std::int64_t>();
            }
            // The speed-up skips frame 1 and is what the recorded times give.
            BootstrapSettings bootstrap;
            bootstrap.statistic = TimeStatistic::Mean;
            const SpeedupInterval expected =
                bootstrapSpeedup(std::vector<double>(fullMs.begin() + 1, fullMs.end()), laterMs, bootstrap);
            const nlohmann::json& s = v.at("speedup_vs_full");
            EXPECT_NEAR(s.at("speedup").get<double>(), expected.speedup, 1e-9);
            EXPECT_EQ(s.at("pairs").get<int>(), frames - 1);
            EXPECT_TRUE(s.at("ci95_low").is_null());  // 3 pairs: no interval
            EXPECT_EQ(v.at("summary").at("ms").at("count").get<int>(), frames - 1);
            EXPECT_GT(v.at("summary").at("reconstruction_counted_bytes").at("median").get<double>(), 0.0);
            EXPECT_EQ(v.at("summary").at("reconstruction_gb_per_s").at("count").get<int>(), frames - 1);
            for (const std::string suffix : {".png", "-heatmap.png", "-heatmap-x4.png"})
                EXPECT_TRUE(fs::exists(dir_ / "render-cache" / (scene + "-48-" + key + suffix)));
        }
        // Reprojected mirror and glass samples are shaded again once the camera moves.
        EXPECT_GT(reshadedLater, 0);
        EXPECT_TRUE(fs::exists(dir_ / "render-cache" / (scene + "-48-full.png")));
    }
    // Goals are stated from the numbers: at 48² the 512² and 1024² ones are not measured.
    ASSERT_FALSE(j.at("goals").empty());
    int mirrorGoals = 0;
    for (const auto& g : j.at("goals")) {
        const std::string goal = g.at("goal");
        if (goal.find("mirror pixels") != std::string::npos) {
            ++mirrorGoals;
            EXPECT_TRUE(g.at("met").is_boolean()) << goal;
        } else {
            EXPECT_TRUE(g.at("met").is_null()) << goal;
        }
    }
    EXPECT_EQ(mirrorGoals, 3);
    const std::string md = readFile(dir_ / "render-cache" / "results.md");
    EXPECT_NE(md.find("Frame 1 traces every pixel"), std::string::npos);
    EXPECT_NE(md.find("| MB counted | GB/s |"), std::string::npos);
    EXPECT_NE(md.find("123 fps (8.1 ms)"), std::string::npos);
    EXPECT_NE(log_.find("render-cache goal, reconstruction ≤ 2.0 ms at 512² (median): not measured at this size"),
              std::string::npos);
}

TEST_F(Experiments, GridsTimesEveryTracerAndAgreesWithEmbree) {
    const nlohmann::json j = results("grids");
    ASSERT_FALSE(j.at("series").empty());
    bool animated = false;
    for (const auto& model : j.at("series")) {
        SCOPED_TRACE(model.at("model").get<std::string>());
        EXPECT_GT(model.at("triangles").get<int>(), 0);
        for (const char* tracer : {"grids", "embree_low", "embree_medium"}) {
            EXPECT_GT(model.at(tracer).at("build_ms").get<double>(), 0.0) << tracer;
            EXPECT_GT(model.at(tracer).at("primary_ms").get<double>(), 0.0) << tracer;
        }
        const auto& agreement = model.at("agreement");
        EXPECT_GT(agreement.at("primary_rays").get<int>(), 0);
        EXPECT_EQ(agreement.at("primary_mismatches").get<int>(), 0);
        EXPECT_EQ(agreement.at("shadow_mismatches").get<int>(), 0);
        animated = animated || model.at("animated").get<bool>();
    }
    EXPECT_TRUE(animated);
}

TEST_F(Experiments, ReportLinksResolveAndStateTheSize) {
    const std::string report = readFile(dir_ / "report.md");
    EXPECT_NE(report.find("Size: tiny"), std::string::npos);
    EXPECT_NE(report.find("Machine and build"), std::string::npos);
    for (const auto& e : allExperiments()) EXPECT_NE(report.find("## " + e->title()), std::string::npos);
    const std::vector<std::vector<std::string>> links = test::TextPattern(R"(\]\(([^)]+)\))").everyMatch(report);
    for (const std::vector<std::string>& link : links) EXPECT_TRUE(fs::exists(dir_ / link[1])) << link[1];
    EXPECT_GT(links.size(), 20u);
    checkMarkdownTables(report, "report.md");
}

TEST_F(Experiments, WhereCachingPaysModelsEverySceneFromItsMeasuredParts) {
    const nlohmann::json j = results("where-caching-pays");
    ASSERT_FALSE(j.at("rows").empty());
    bool animated = false;
    for (const auto& row : j.at("rows")) {
        SCOPED_TRACE(row.at("scene").get<std::string>());
        const double coverage = row.at("mirror_glass_coverage").get<double>();
        EXPECT_GT(coverage, 0.0);  // every scene of the map shows a mirror or glass
        EXPECT_LE(coverage, 1.0);
        animated = animated || row.at("animated").get<bool>();
        for (const char* technique : {"cct", "cdct"})
            for (const char* part : {"still", "path"}) {
                SCOPED_TRACE(std::string(technique) + " " + part);
                const auto& t = row.at(technique).at(part);
                const auto& p = t.at("parts");
                const double uncached = p.at("uncached_ms").get<double>(), ideal = p.at("ideal_ms").get<double>();
                EXPECT_GT(uncached, 0.0);
                EXPECT_GT(ideal, 0.0);
                EXPECT_GT(p.at("leaving_rays").get<std::uint64_t>(), 0u);
                const double hitRate = p.at("hit_rate").get<double>();
                EXPECT_GE(hitRate, 0.0);
                EXPECT_LE(hitRate, 1.0);
                // The reported prediction is the model applied to the reported parts.
                const double trees = uncached - ideal + p.at("ideal_lookup_ms").get<double>();
                EXPECT_NEAR(p.at("cacheable_tree_ms").get<double>(), trees, 1e-9 * uncached);
                const double frame = uncached - hitRate * trees + p.at("lookup_ms").get<double>() +
                                     p.at("frame_end_ms").get<double>();
                EXPECT_NEAR(t.at("predicted").get<double>(), uncached / frame, 1e-9 * uncached / frame);
                // The free cache's bound is the uncached frame over what lies outside the trees.
                if (trees < uncached) {
                    EXPECT_NEAR(p.at("free_cache_speedup").get<double>(), uncached / (uncached - trees),
                                1e-9 * uncached / (uncached - trees));
                }
            }
    }
    EXPECT_TRUE(animated);
    for (const auto& row : j.at("rows")) {
        const double bypassed = row.at("cct_auto").at("path_bypassed_share").get<double>();
        EXPECT_GE(bypassed, 0.0);
        EXPECT_LE(bypassed, 1.0);
    }
    const std::string md = readFile(dir_ / "where-caching-pays" / "results.md");
    EXPECT_NE(md.find("--cache-policy auto"), std::string::npos);
    EXPECT_NE(md.find("### CCT"), std::string::npos);
    EXPECT_NE(md.find("### CDCT"), std::string::npos);
}
