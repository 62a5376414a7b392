// core_speed and cct_speed with --json, at tiny size: the document holds
// every field scripts/doc-figures.py reads to write the docs' figures from
// the committed runs (docs/bench-runs/), its figures agree with each other,
// and a --json path that cannot be written stops the program before it
// measures anything: exit 2, one line, no file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
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

TEST_F(BenchmarkJson, AJsonPathThatCannotBeWrittenStopsBeforeMeasuring) {
    const fs::path missing = dir_.path() / "missing" / "run.json";
    const fs::path blocked = dir_.path() / "a-file" / "run.json";
    std::ofstream(dir_.path() / "a-file") << "in the way\n";
    for (const char* program : {"core_speed", "cct_speed"})
        for (const fs::path& path : {missing, blocked, dir_.path()}) {
            const auto result = run(benchmark(program) + " --size 16 --rounds 1 --warmup 0 --threads 1 --scenes " +
                                    "grid-1 --json " + path.string());
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

}  // namespace
