// The standalone benchmarks with --json, at tiny size: the document holds
// every field scripts/doc-figures.py reads to write the docs' figures from
// the committed runs (docs/bench-runs/), its figures agree with each other
// and with the table printed, and a --json path that cannot be written stops
// the program before it measures anything: exit 2, one line, no file.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "TempDir.h"
#include "app/ShellRun.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string benchmark(const std::string& name) {
    return (fs::path(RAYCACHE_BENCHMARKS_DIR) / name).string();
}

json readJson(const fs::path& path) {
    std::ifstream in(path);
    return json::parse(in);
}

// The fields of one variant's timings that the docs quote.
void expectTimings(const json& variant, const std::string& where) {
    for (const char* key : {"median_ms", "min_ms", "max_ms"}) {
        ASSERT_TRUE(variant.contains(key) && variant[key].is_number()) << where << " has no " << key;
        EXPECT_GT(variant[key].get<double>(), 0.0) << where << " " << key;
    }
    EXPECT_LE(variant["min_ms"].get<double>(), variant["median_ms"].get<double>()) << where;
    EXPECT_GE(variant["max_ms"].get<double>(), variant["median_ms"].get<double>()) << where;
    ASSERT_TRUE(variant.contains("rays") && variant["rays"].is_number_unsigned()) << where;
    EXPECT_GT(variant["rays"].get<std::uint64_t>(), 0u) << where;
}

// A summary of samples (BenchmarkRecord's summaryJson): `count` samples, their median, min and max.
void expectSummary(const json& summary, std::size_t count, const std::string& where, const std::string& unit = "ms") {
    ASSERT_TRUE(summary.is_object()) << where;
    ASSERT_EQ(summary["samples_" + unit].size(), count) << where;
    const double median = summary["median_" + unit].get<double>();
    EXPECT_LE(summary["min_" + unit].get<double>(), median) << where;
    EXPECT_GE(summary["max_" + unit].get<double>(), median) << where;
}

double medianMs(const json& timings) { return timings["median_ms"].get<double>(); }

// The number as the benchmarks' tables print it.
std::string printed(const char* format, double value) {
    char text[32];
    std::snprintf(text, sizeof text, format, value);
    return text;
}

// What every benchmark's document holds besides its figures: the provenance doc-figures prints.
void expectProvenance(const json& run, const std::string& program, const std::string& options) {
    EXPECT_EQ(run["benchmark"], program);
    ASSERT_TRUE(run["command"].is_string());
    EXPECT_NE(run["command"].get<std::string>().find(options), std::string::npos) << run["command"];
    EXPECT_NE(run["command"].get<std::string>().find("--json"), std::string::npos) << run["command"];
    const json& env = run["environment"];
    EXPECT_TRUE(env["cpu_model"].is_string());
    EXPECT_EQ(env["worker_threads"], 1);
    EXPECT_TRUE(env["version"]["lanes"].is_string());
    EXPECT_TRUE(env["version"]["git_commit"].is_string());
    EXPECT_EQ(env["started_at"].get<std::string>().size(), 20u) << env["started_at"];  // 2026-01-31T12:00:00Z
    EXPECT_TRUE(run["lane_level"].is_string());
    EXPECT_TRUE(run["lanes_requested"].is_null()) << run["lanes_requested"];
    ASSERT_TRUE(run["git_commit"].is_string());
    ASSERT_TRUE(run["dirty"].is_boolean());
    EXPECT_EQ(env["version"]["git_commit"].get<std::string>(),
              run["git_commit"].get<std::string>() + (run["dirty"].get<bool>() ? "-dirty" : ""));
    EXPECT_TRUE(run["others_cpu_share"].is_number() || run["others_cpu_share"].is_null());
}

class BenchmarkJson : public ::testing::Test {
protected:
    raycache::TempDir dir_{"benchmark-json"};

    raycache::test::RunResult run(const std::string& command) const {
        return raycache::test::runShell(command, dir_.path() / "stderr.txt");
    }
};

TEST_F(BenchmarkJson, CoreSpeedWritesEveryFigureTheDocsQuote) {
    const fs::path out = dir_.path() / "core.json";
    const std::string options = "--size 24 --rounds 2 --warmup 0 --threads 1 --scenes grid-2";
    const auto result = run(benchmark("core_speed") + " " + options + " --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("| grid-2 | ideal frame / floor |"), std::string::npos) << result.out;
    const json doc = readJson(out);
    expectProvenance(doc, "core_speed", options);
    const json& settings = doc["settings"];
    EXPECT_EQ(settings["size"], 24);
    EXPECT_EQ(settings["rounds"], 2);
    EXPECT_EQ(settings["max_depth"], 5);
    EXPECT_EQ(settings["scenes"], json::array({"grid-2"}));
    ASSERT_EQ(doc["scenes"].size(), 1u);
    const json& scene = doc["scenes"][0];
    EXPECT_EQ(scene["scene"], "grid-2");
    const json& v = scene["variants"];
    for (const char* variant : {"plain_loop", "plain_loop_raycache_bvh", "raycache", "ideal", "floor"}) {
        ASSERT_TRUE(v.contains(variant)) << variant;
        expectTimings(v[variant], variant);
        EXPECT_EQ(v[variant]["frame_ms"].size(), 2u) << variant;
    }
    EXPECT_DOUBLE_EQ(scene["ideal_over_floor"].get<double>(),
                     v["ideal"]["median_ms"].get<double>() / v["floor"]["median_ms"].get<double>());
    EXPECT_DOUBLE_EQ(scene["uncached_over_plain_loop"].get<double>(),
                     v["raycache"]["median_ms"].get<double>() / v["plain_loop"]["median_ms"].get<double>());
    const json& stages = scene["ideal_frame_stages"];
    ASSERT_TRUE(stages.is_object()) << stages;
    EXPECT_GT(stages["hits_shaded"].get<std::uint64_t>(), 0u);
    EXPECT_GT(stages["ns_per_hit"]["all"].get<double>(), 0.0);
    EXPECT_TRUE(stages["floor_ns_per_camera_hit"].is_number());
}

TEST_F(BenchmarkJson, CoreSpeedRecordsTheLaneLevelAsked) {
    const fs::path out = dir_.path() / "core-avx2.json";
    const auto result = run("RAYCACHE_LANES=avx2 " + benchmark("core_speed") +
                            " --size 16 --rounds 1 --warmup 0 --threads 1 --scenes grid-1 --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json doc = readJson(out);
    EXPECT_EQ(doc["lanes_requested"], "avx2");
    // Narrowed to AVX2, or baseline where the processor or the build has no AVX2.
    EXPECT_TRUE(doc["lane_level"] == "avx2" || doc["lane_level"] == "baseline") << doc["lane_level"];
    EXPECT_NE(doc["environment"]["version"]["lanes"].get<std::string>().find("RAYCACHE_LANES"), std::string::npos);
}

TEST_F(BenchmarkJson, CctSpeedWritesEveryFigureTheDocsQuote) {
    const fs::path out = dir_.path() / "cct.json";
    const std::string options =
        "--size 24 --rounds 2 --warmup 1 --path-frames 2 --path-rounds 1 --threads 1 --scenes grid-2";
    const auto result = run(benchmark("cct_speed") + " " + options + " --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("## (b) moving camera path"), std::string::npos) << result.out;
    const json doc = readJson(out);
    expectProvenance(doc, "cct_speed", options);
    const json& settings = doc["settings"];
    EXPECT_EQ(settings["size"], 24);
    EXPECT_EQ(settings["path_frames"], 2);
    EXPECT_EQ(settings["max_depth"], 5);
    EXPECT_EQ(settings["scenes"], json::array({"grid-2"}));
    ASSERT_EQ(doc["scenes"].size(), 1u);
    const json& scene = doc["scenes"][0];
    EXPECT_EQ(scene["scene"], "grid-2");
    const json& still = scene["still"];
    for (const char* variant : {"uncached", "cct", "ideal"})
        expectTimings(still[variant], std::string("still ") + variant);
    EXPECT_DOUBLE_EQ(still["speedup"].get<double>(),
                     still["uncached"]["median_ms"].get<double>() / still["cct"]["median_ms"].get<double>());
    EXPECT_DOUBLE_EQ(still["ideal_speedup"].get<double>(),
                     still["uncached"]["median_ms"].get<double>() / still["ideal"]["median_ms"].get<double>());
    EXPECT_DOUBLE_EQ(still["documents_speedup"].get<double>(), 1.07);  // the documents' Table 5.2, grid-2
    EXPECT_GT(still["cache_mib"].get<double>(), 0.0);
    const json& path = scene["path"];
    for (const char* variant : {"uncached", "cct", "ideal"})
        expectTimings(path[variant], std::string("path ") + variant);
    EXPECT_DOUBLE_EQ(path["speedup"].get<double>(),
                     path["uncached"]["median_ms"].get<double>() / path["cct"]["median_ms"].get<double>());
    ASSERT_TRUE(path.contains("miss_over_plain_trace"));
    EXPECT_TRUE(path["miss_over_plain_trace"].is_number() || path["miss_over_plain_trace"].is_null());
    EXPECT_TRUE(path["cct_hit_percent_last_frame"].is_number());
}

TEST_F(BenchmarkJson, HybridSpeedWritesEveryFigureOfItsTables) {
    const fs::path out = dir_.path() / "hybrid.json";
    const std::string options = "--size 16 --rounds 2 --warmup 1 --threads 1 --scenes behind-2 --parts abc";
    const auto result = run(benchmark("hybrid_speed") + " " + options + " --json " + out.string());
    if (result.exitCode == 1 && result.err.find("no OpenGL") != std::string::npos)
        GTEST_SKIP() << "no OpenGL context here: " << result.err;
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json doc = readJson(out);
    expectProvenance(doc, "hybrid_speed", options);
    EXPECT_EQ(doc["settings"]["parts"], "abc");
    EXPECT_EQ(doc["settings"]["scenes"], json::array({"behind-2"}));
    ASSERT_EQ(doc["gbuffer_only"].size(), 1u);
    const json& gbuffer = doc["gbuffer_only"][0];
    EXPECT_EQ(gbuffer["scene"], "behind-2");
    expectTimings(gbuffer["packets"], "packets");
    expectSummary(gbuffer["opengl_raster"], 2, "raster");
    expectSummary(gbuffer["opengl_readback"], 2, "readback");
    EXPECT_DOUBLE_EQ(gbuffer["opengl_over_packets"].get<double>(),
                     medianMs(gbuffer["opengl"]) / medianMs(gbuffer["packets"]));
    ASSERT_EQ(doc["whole_frames"].size(), 1u);
    const json& frames = doc["whole_frames"][0];
    for (const char* variant : {"ray", "hybrid_opengl", "hybrid_packets"}) expectTimings(frames[variant], variant);
    const double rayOverHybrid = medianMs(frames["ray"]) / medianMs(frames["hybrid_opengl"]);
    EXPECT_DOUBLE_EQ(frames["ray_over_hybrid_opengl"].get<double>(), rayOverHybrid);
    EXPECT_NE(result.out.find(printed("| %.2fx |", rayOverHybrid)), std::string::npos) << result.out;
    // Each timed OpenGL frame's phases (the warm-up frame's are left out).
    for (const char* phase : {"raster", "readback", "shadows", "secondary", "compose"})
        expectSummary(frames["hybrid_opengl_phases"][phase], 2, phase);
    ASSERT_EQ(doc["table_5_1"].size(), 7u);
    const json& behind32 = doc["table_5_1"][6];
    EXPECT_EQ(behind32["n"], 32);
    EXPECT_DOUBLE_EQ(behind32["documents_speedup"].get<double>(), 3.50);
    for (const char* variant : {"hybrid", "hybrid_cct_main", "hybrid_cct_all", "ray"})
        expectTimings(behind32[variant], variant);
    EXPECT_DOUBLE_EQ(behind32["speedup_all"].get<double>(),
                     medianMs(behind32["hybrid"]) / medianMs(behind32["hybrid_cct_all"]));
}

TEST_F(BenchmarkJson, MovingCacheWritesEveryFigureOfItsTables) {
    const fs::path out = dir_.path() / "moving.json";
    const std::string options =
        "--size 16 --frames 3 --rounds 2 --threads 1 --scenes grid-2 --no-multi-res --view --fill --view-fill";
    const auto result = run(benchmark("moving_cache") + " " + options + " --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json doc = readJson(out);
    expectProvenance(doc, "moving_cache", options);
    EXPECT_EQ(doc["settings"]["frames"], 3);
    EXPECT_EQ(doc["settings"]["multi_res"], false);
    ASSERT_EQ(doc["scenes"].size(), 1u);
    EXPECT_EQ(doc["scenes"][0]["scene"], "grid-2");
    const json& variants = doc["scenes"][0]["variants"];
    EXPECT_EQ(variants.size(), 5u) << variants;
    EXPECT_FALSE(variants.contains("cct_multi_res"));
    const json& uncached = variants["uncached"];
    EXPECT_FALSE(uncached.contains("frames"));  // the other variants' truth
    expectTimings(uncached["timing"], "uncached");
    EXPECT_EQ(uncached["timing"]["frame_ms"].size(), 2u);
    for (const char* key : {"cct", "cct_from_view", "cct_fill", "cct_from_view_fill"}) {
        const json& v = variants[key];
        ASSERT_EQ(v["frames"].size(), 3u) << key;
        for (const json& frame : v["frames"]) {
            EXPECT_GE(frame["hit_percent"].get<double>(), 0.0) << key;
            EXPECT_GT(frame["cache_mib"].get<double>(), 0.0) << key;
            EXPECT_TRUE(frame["psnr_db"].is_number() || frame["psnr_db"].is_null()) << key;
        }
        EXPECT_TRUE(v["frames"][0]["psnr_db"].is_null()) << "frame 1 traces everything: " << key;
        EXPECT_TRUE(v.contains("mean_psnr_db")) << key;
        expectTimings(v["timing"], key);
        EXPECT_DOUBLE_EQ(v["speedup"].get<double>(), medianMs(uncached["timing"]) / medianMs(v["timing"])) << key;
        const std::string row = "| " + v["name"].get<std::string>() + " | " +
                                printed("%.1f", medianMs(v["timing"])) + " (";
        EXPECT_NE(result.out.find(row), std::string::npos) << row << " not in\n" << result.out;
    }
}

TEST_F(BenchmarkJson, SceneUpdateSpeedWritesEveryFigureOfItsTable) {
    const fs::path out = dir_.path() / "update.json";
    const std::string options = "--size 16 --frames 3 --rounds 1 --threads 1";
    const auto result = run(benchmark("scene_update_speed") + " " + options + " --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json doc = readJson(out);
    expectProvenance(doc, "scene_update_speed", options);
    EXPECT_EQ(doc["settings"]["frames"], 3);
    std::map<std::string, const json*> rows;
    for (const json& v : doc["variants"])
        rows[v["scene"].get<std::string>() + " " + v["variant"].get<std::string>()] = &v;
    EXPECT_EQ(rows.size(), 10u);
    for (const char* row : {"cloth refit, uncached", "cloth rebuild, uncached", "orbit CCT", "light-sweep uncached"})
        ASSERT_TRUE(rows.count(row)) << row;
    for (const auto& [name, v] : rows) {
        // Frame 0 of each round is left out.
        for (const char* part : {"update", "render", "frame"}) expectSummary((*v)[part], 2, name + " " + part);
        expectSummary((*v)["update_share"], 2, name + " share", "percent");
    }
    const json& refit = *rows["cloth refit, uncached"];
    EXPECT_NE(result.out.find("| cloth | refit, uncached | " + printed("%.2f", medianMs(refit["update"])) + " ("),
              std::string::npos)
        << result.out;
}

TEST_F(BenchmarkJson, GridsSpeedWritesEveryFigureItPrints) {
    const fs::path out = dir_.path() / "grids.json";
    const std::string options = "--model 'torus 10k' --size 16 --rounds 2 --threads 1";
    const auto result = run(benchmark("grids_speed") + " " + options + " --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json doc = readJson(out);
    expectProvenance(doc, "grids_speed", options);
    EXPECT_EQ(doc["settings"]["model"], "torus 10k");
    for (const char* part : {"build", "camera_grid", "light_grids", "primary", "shadow", "total"})
        expectSummary(doc["grids"][part], 2, std::string("grids ") + part);
    for (const char* part : {"build", "primary", "shadow", "total"})
        expectSummary(doc["embree"][part], 2, std::string("embree ") + part);
    EXPECT_GT(doc["shadow_rays"].get<std::uint64_t>(), 0u);
    const json &grids = doc["grids"], &embree = doc["embree"];
    const double rays = (medianMs(grids["primary"]) + medianMs(grids["shadow"])) /
                        (medianMs(embree["primary"]) + medianMs(embree["shadow"]));
    EXPECT_DOUBLE_EQ(doc["rays_over_embree"].get<double>(), rays);
    EXPECT_DOUBLE_EQ(doc["total_over_embree"].get<double>(), medianMs(grids["total"]) / medianMs(embree["total"]));
    EXPECT_NE(result.out.find("rays alone (primary + shadow) " + printed("%.2fx", rays)), std::string::npos)
        << result.out;
}

TEST_F(BenchmarkJson, SoakWritesEveryFigureItPrints) {
    const fs::path out = dir_.path() / "soak.json";
    const std::string options = "--frames 4 --size 8 --every 2 --cache-res 16 --threads 1";
    const auto result = run(benchmark("soak") + " " + options + " --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json doc = readJson(out);
    expectProvenance(doc, "soak", options);
    EXPECT_EQ(doc["settings"]["scene"], "room");
    EXPECT_EQ(doc["settings"]["technique"], "cct");
    ASSERT_EQ(doc["samples"].size(), 3u);  // frame 1, then every 2 frames
    const int frames[] = {1, 2, 4};
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(doc["samples"][i]["frame"].get<int>(), frames[i]);
    for (const json& sample : doc["samples"]) {
        EXPECT_GT(sample["resident_kib"].get<double>(), 0.0);
        EXPECT_GT(sample["heap_kib"].get<double>(), 0.0);
        EXPECT_TRUE(sample["hit_percent"].is_number() && sample["invalid_percent"].is_number());
    }
    const json& half = doc["second_half"];
    EXPECT_EQ(half["from_frame"], 2);
    EXPECT_EQ(half["to_frame"], 4);
    EXPECT_NE(result.out.find(printed("resident %+.0f KiB", half["resident_growth_kib"].get<double>())),
              std::string::npos)
        << result.out;
}

TEST_F(BenchmarkJson, SceneLoadSpeedWritesEveryFigureOfItsTable) {
    const fs::path out = dir_.path() / "load.json";
    const std::string options = "--rounds 2 --scenes bunny-glass";
    const auto result = run(benchmark("scene_load_speed") + " " + options + " --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json doc = readJson(out);
    expectProvenance(doc, "scene_load_speed", options);
    ASSERT_EQ(doc["scenes"].size(), 1u);
    const json& scene = doc["scenes"][0];
    EXPECT_EQ(scene["scene"], "bunny-glass");
    EXPECT_GT(scene["triangles"].get<std::uint64_t>(), 3674u);  // the bunny and its floor
    expectSummary(scene["load"], 2, "load");
    EXPECT_NE(result.out.find("| bunny-glass | " + std::to_string(scene["triangles"].get<std::uint64_t>()) + " | " +
                              printed("%.1f", medianMs(scene["load"])) + " |"),
              std::string::npos)
        << result.out;
}

TEST_F(BenchmarkJson, CdctSpeedWritesEveryFigureOfItsQualityAndSpeedTables) {
    const fs::path out = dir_.path() / "cdct.json";
    const std::string options = "--width 32 --height 16 --rounds 2 --warmup 1 --threads 1 --cache-res 16 "
                                "--quality-scenes parallax --quality-size 16 --quality-frames 3";
    const auto result = run(benchmark("cdct_speed") + " " + options + " --json " + out.string());
    ASSERT_EQ(result.exitCode, 0) << result.err;
    const json doc = readJson(out);
    expectProvenance(doc, "cdct_speed", options);
    const json& settings = doc["settings"];
    EXPECT_EQ(settings["parts"], json::array({"quality", "speed"}));
    EXPECT_EQ(settings["width"], 32);
    EXPECT_EQ(settings["quality_frames"], 3);
    EXPECT_EQ(settings["cache_res"], 16);

    ASSERT_EQ(doc["quality"].size(), 1u);
    const json& quality = doc["quality"][0];
    EXPECT_EQ(quality["scene"], "parallax");
    EXPECT_EQ(quality["size"], 16);
    EXPECT_EQ(quality["face_resolution"], 16);
    ASSERT_EQ(quality["variants"].size(), 2u);
    EXPECT_EQ(quality["variants"][0]["technique"], "cct");
    EXPECT_EQ(quality["variants"][1]["technique"], "cdct-parity");
    // The improved CDCT's changes switched on one after another: the last row is `cdct` itself.
    const json& ladder = quality["improvements_one_by_one"];
    ASSERT_EQ(ladder.size(), 9u);
    for (std::size_t i = 0; i < ladder.size(); ++i) EXPECT_EQ(ladder[i]["improvements_on"], i + 1) << i;
    for (const json& v : quality["variants"]) {
        const double mean = v["mean_psnr_db"].get<double>(), lowest = v["min_psnr_db"].get<double>();
        EXPECT_LE(lowest, mean) << v["name"];
        const std::string row = "| " + v["name"].get<std::string>() + " | " + printed("%.2f", mean) + " | " +
                                printed("%.2f", lowest) + " | " + printed("%.2f", v["last_psnr_db"].get<double>()) +
                                " | " + printed("%.1f%%", v["hit_percent"].get<double>()) + " | " +
                                printed("%.1f%%", v["rejected_percent"].get<double>()) + " |";
        EXPECT_NE(result.out.find(row), std::string::npos) << row << " not in\n" << result.out;
    }

    ASSERT_EQ(doc["speed"].size(), 2u);
    EXPECT_EQ(doc["speed"][0]["scene"], "diffuse-32");
    EXPECT_EQ(doc["speed"][1]["scene"], "reflective-32");
    for (const json& table : doc["speed"]) {
        const std::string scene = table["scene"];
        EXPECT_EQ(table["width"], 32);
        EXPECT_EQ(table["face_resolution"], 16);
        const json& variants = table["variants"];
        ASSERT_EQ(variants.size(), 7u) << scene;
        EXPECT_EQ(variants[1]["technique"], "none");
        const json& improved = variants[6];
        EXPECT_EQ(improved["technique"], "cdct");
        EXPECT_EQ(improved["improvements_on"], 9);
        EXPECT_EQ(table["improvements_one_by_one"].size(), 9u) << scene;
        const double uncached = medianMs(variants[1]);
        for (const json& v : variants) {
            expectTimings(v, scene + " " + v["name"].get<std::string>());
            EXPECT_EQ(v["frame_ms"].size(), 2u);
            EXPECT_DOUBLE_EQ(v["speedup_vs_uncached"].get<double>(), uncached / medianMs(v)) << v["name"];
        }
        EXPECT_TRUE(improved["documents_fps"].is_null());
        EXPECT_EQ(variants[4]["step"], 0.2);  // CDCT parity 0.2/0.02, as written
        EXPECT_EQ(variants[4]["epsilon"], 0.02);
        const std::string row = "| CDCT improved (cdct) | " + printed("%.1f", medianMs(improved)) + " (" +
                                printed("%.1f", improved["min_ms"].get<double>()) + "-" +
                                printed("%.1f", improved["max_ms"].get<double>()) + ") | " +
                                printed("%.1f", 1000.0 / medianMs(improved)) + " | " +
                                printed("%.2fx", improved["speedup_vs_uncached"].get<double>()) + " | ";
        EXPECT_NE(result.out.find(row), std::string::npos) << row << " not in\n" << result.out;
    }
    // The documents' Table 5.3: CCT and uncached on diffuse-32, frames per second.
    EXPECT_DOUBLE_EQ(doc["speed"][0]["variants"][0]["documents_fps"].get<double>(), 76.0);
    EXPECT_DOUBLE_EQ(doc["speed"][0]["variants"][0]["documents_speedup"].get<double>(), 76.0 / 69.6);
}

TEST_F(BenchmarkJson, AJsonPathThatCannotBeWrittenStopsBeforeMeasuring) {
    const fs::path missing = dir_.path() / "missing" / "run.json";
    const fs::path blocked = dir_.path() / "a-file" / "run.json";
    std::ofstream(dir_.path() / "a-file") << "in the way\n";
    const std::string sceneOptions = " --size 16 --rounds 1 --warmup 0 --threads 1 --scenes grid-1";
    const std::map<std::string, std::string> programs = {
        {"core_speed", sceneOptions},
        {"cct_speed", sceneOptions},
        {"hybrid_speed", " --size 16 --rounds 1 --warmup 0 --threads 1 --scenes behind-0 --parts b"},
        {"moving_cache", " --size 16 --frames 2 --rounds 1 --threads 1 --scenes grid-1"},
        {"scene_update_speed", " --size 16 --frames 2 --rounds 1 --threads 1"},
        {"grids_speed", " --model 'torus 10k' --size 16 --rounds 1 --threads 1"},
        {"soak", " --frames 2 --size 8 --every 1 --cache-res 16 --threads 1"},
        {"scene_load_speed", " --rounds 1 --scenes grid-1"},
        {"cdct_speed", " --width 16 --height 16 --rounds 1 --warmup 0 --threads 1 --cache-res 16 --quality-size 16"
                       " --quality-frames 2"},
    };
    for (const auto& [program, options] : programs)
        for (const fs::path& path : {missing, blocked, dir_.path()}) {
            const auto result = run(benchmark(program) + options + " --json " + path.string());
            EXPECT_EQ(result.exitCode, 2) << program << " " << path << ": " << result.err;
            EXPECT_EQ(raycache::test::lineCount(result.err), 1) << program << ": " << result.err;
            EXPECT_EQ(result.err.rfind("error: --json ", 0), 0u) << result.err;
            EXPECT_TRUE(result.out.empty()) << program << " measured before checking its --json path";
        }
    EXPECT_FALSE(fs::exists(missing.parent_path()));
    // Nothing left behind: no JSON, no temporary or probe file.
    for (const auto& entry : fs::directory_iterator(dir_.path())) {
        const std::string name = entry.path().filename().string();
        EXPECT_TRUE(name == "a-file" || name == "stderr.txt") << "left behind: " << name;
    }
}

// A face resolution outside the caches' limits is refused on one line
// before anything runs, as `raycache render` refuses it, not thrown later
// from inside the first frame.
TEST_F(BenchmarkJson, AFaceResolutionOutsideTheLimitsIsOneLineBeforeMeasuring) {
    for (const std::string program : {"soak", "cdct_speed"})
        for (const std::string resolution : {"8", "4096"}) {
            const auto result = run(benchmark(program) + " --cache-res " + resolution);
            EXPECT_NE(result.exitCode, 0) << program << " " << resolution;
            EXPECT_LT(result.exitCode, 128) << program << " " << resolution << " crashed: " << result.err;
            EXPECT_NE(result.err.find("--cache-res"), std::string::npos) << result.err;
            EXPECT_TRUE(result.out.empty()) << program << " measured with --cache-res " << resolution;
        }
}

}  // namespace
