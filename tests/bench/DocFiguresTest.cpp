// scripts/doc-figures.py on --tiny runs of every standalone benchmark
// (scripts/record-bench-runs.sh --tiny --programs all --out DIR), written
// into a copy of README.md, docs/performance.md and docs/dynamic-scenes.md:
// every block of the benchmarks is generated from its runs, its figures
// are the medians of the runs' medians with min–max over the runs, --check
// passes on what it wrote and fails on a figure changed by hand, and a
// block whose runs are missing stays as it was and is named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/ShellRun.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::vector<std::string> kPrograms = {"core_speed",   "cct_speed",          "hybrid_speed",
                                            "moving_cache", "scene_update_speed", "grids_speed",
                                            "soak",         "scene_load_speed",   "cdct_speed"};

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), {}};
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

// `text` with its line breaks as spaces: the generated prose is wrapped anywhere.
std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
}

// The block between `<!-- figures:NAME -->` and the next `<!-- /figures -->`, markers included; empty if none.
std::string block(const std::string& doc, const std::string& name) {
    const std::size_t begin = doc.find("<!-- figures:" + name + " -->");
    if (begin == std::string::npos) return {};
    const std::string end = "<!-- /figures -->";
    return doc.substr(begin, doc.find(end, begin) + end.size() - begin);
}

// "median (min–max)" with one decimal, as doc-figures writes times.
std::string msCell(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    const double median = n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2.0;
    char text[64];
    std::snprintf(text, sizeof text, "%.1f (%.1f–%.1f)", median, values.front(), values.back());
    return text;
}

class DocFigures : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = fs::temp_directory_path() / ("raycache-doc-figures-" + std::to_string(static_cast<long>(::getpid())));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        // hybrid_speed needs an OpenGL context (EGL, llvmpipe); without one its block is not tried.
        programs_ = kPrograms;
        const auto probe =
            run(benchmark("hybrid_speed") + " --size 8 --rounds 1 --warmup 0 --threads 1 --scenes behind-0 --parts a");
        if (probe.exitCode != 0) programs_.erase(std::find(programs_.begin(), programs_.end(), "hybrid_speed"));
        std::string list;
        for (const std::string& p : programs_) list += (list.empty() ? "" : ",") + p;
        recording_ = run(source("scripts/record-bench-runs.sh") + " --tiny --programs " + list + " --out " +
                         runs().string() + " --bin " + std::string(RAYCACHE_BENCHMARKS_DIR) + " 2");
    }
    static void TearDownTestSuite() { fs::remove_all(dir_); }

    void SetUp() override {
        ASSERT_EQ(recording_.exitCode, 0) << recording_.out << recording_.err;
        if (std::find(programs_.begin(), programs_.end(), "hybrid_speed") == programs_.end())
            std::printf("no OpenGL context here: hybrid_speed's block is not tried\n");
    }

    static std::string source(const std::string& relative) {
        return (fs::path(RAYCACHE_SOURCE_DIR) / relative).string();
    }
    static std::string benchmark(const std::string& name) {
        return (fs::path(RAYCACHE_BENCHMARKS_DIR) / name).string();
    }
    static fs::path runs() { return dir_ / "runs"; }
    static raycache::test::RunResult run(const std::string& command) {
        return raycache::test::runShell(command, dir_ / "stderr.txt");
    }

    // A copy of the docs doc-figures writes, in a tree of its own named `name`.
    static fs::path copyOfTheDocs(const std::string& name) {
        const fs::path tree = dir_ / name;
        fs::create_directories(tree / "docs");
        fs::copy_file(source("README.md"), tree / "README.md");
        for (const char* doc : {"performance.md", "dynamic-scenes.md"})
            fs::copy_file(source("docs/" + std::string(doc)), tree / "docs" / doc);
        return tree;
    }

    static raycache::test::RunResult docFigures(const fs::path& runsDir, const fs::path& tree,
                                                const std::string& mode = "") {
        return run(source("scripts/doc-figures.py") + " --bench-runs " + runsDir.string() + " --docs " + tree.string() +
                   mode);
    }

    static json readRuns(const std::string& program) {
        json documents = json::array();
        for (const auto& entry : fs::directory_iterator(runs() / program)) {
            std::ifstream in(entry.path());
            documents.push_back(json::parse(in));
        }
        return documents;
    }

    static bool recorded(const std::string& program) {
        return std::find(programs_.begin(), programs_.end(), program) != programs_.end();
    }

    static inline fs::path dir_;
    static inline std::vector<std::string> programs_;
    static inline raycache::test::RunResult recording_;
};

TEST_F(DocFigures, EveryBenchmarkBlockIsGeneratedFromItsTinyRuns) {
    const fs::path tree = copyOfTheDocs("generated");
    const auto result = docFigures(runs(), tree);
    ASSERT_EQ(result.exitCode, 0) << result.out << result.err;
    EXPECT_EQ(result.out.find("not generated"), std::string::npos) << result.out;
    const std::string performance = readText(tree / "docs/performance.md");
    const std::vector<std::pair<std::string, std::string>> blocks = {{"bench-hybrid", "hybrid_speed"},
                                                                     {"bench-moving-cache", "moving_cache"},
                                                                     {"bench-scene-update", "scene_update_speed"},
                                                                     {"bench-grids", "grids_speed"},
                                                                     {"bench-soak", "soak"},
                                                                     {"bench-scene-load", "scene_load_speed"},
                                                                     {"bench-cdct", "cdct_speed"}};
    for (const auto& [name, program] : blocks) {
        if (!recorded(program)) continue;
        const std::string text = oneLine(block(performance, name));
        ASSERT_FALSE(text.empty()) << name;
        // The tiny run's command and its provenance line.
        EXPECT_NE(text.find("`build/release/benchmarks/" + program + " "), std::string::npos) << text;
        EXPECT_NE(text.find("generated by `scripts/doc-figures.py` from `docs/bench-runs/" + program + "/`"),
                  std::string::npos)
            << text;
        EXPECT_NE(text.find(program == "soak" ? "1 run;" : "2 runs"), std::string::npos) << text;
    }
    const std::string table = block(readText(tree / "docs/dynamic-scenes.md"), "bench-scene-update-table");
    EXPECT_NE(table.find("| cloth | rebuild, uncached | "), std::string::npos) << table;
    EXPECT_NE(table.find("docs/bench-runs/scene_update_speed/"), std::string::npos) << table;
    // What it wrote is what it checks.
    const auto check = docFigures(runs(), tree, " --check");
    EXPECT_EQ(check.exitCode, 0) << check.out << check.err;
}

TEST_F(DocFigures, TimesAreTheMediansOfTheRunsMediansWithTheirRange) {
    const fs::path tree = copyOfTheDocs("medians");
    ASSERT_EQ(docFigures(runs(), tree).exitCode, 0);
    const std::string grids = oneLine(block(readText(tree / "docs/performance.md"), "bench-grids"));
    std::vector<double> gridsTotal, embreeTotal;
    for (const json& r : readRuns("grids_speed")) {
        if (r["settings"]["model"] != "torus 100k") continue;
        gridsTotal.push_back(r["grids"]["total"]["median_ms"].get<double>());
        embreeTotal.push_back(r["embree"]["total"]["median_ms"].get<double>());
    }
    ASSERT_EQ(gridsTotal.size(), 2u);
    EXPECT_NE(grids.find("torus 100k " + msCell(gridsTotal) + " against " + msCell(embreeTotal) + " ms"),
              std::string::npos)
        << msCell(gridsTotal) << " against " << msCell(embreeTotal) << " not in\n"
        << grids;
}

TEST_F(DocFigures, CdctFrameTimesAreTheMediansOfTheSpeedRunsMedians) {
    const fs::path tree = copyOfTheDocs("cdct");
    ASSERT_EQ(docFigures(runs(), tree).exitCode, 0);
    const std::string cdct = oneLine(block(readText(tree / "docs/performance.md"), "bench-cdct"));
    std::vector<double> improved, uncached;
    for (const json& r : readRuns("cdct_speed"))
        for (const json& table : r["speed"]) {
            if (table["scene"] != "reflective-32") continue;
            for (const json& v : table["variants"]) {
                if (v["technique"] == "cdct") improved.push_back(v["median_ms"].get<double>());
                if (v["technique"] == "none") uncached.push_back(v["median_ms"].get<double>());
            }
        }
    ASSERT_EQ(improved.size(), 2u);  // the two --speed-only runs; the --quality-only ones have no speed tables
    EXPECT_NE(cdct.find("on reflective-32 (" + msCell(improved) + " against " + msCell(uncached) + " ms)"),
              std::string::npos)
        << msCell(improved) << " against " << msCell(uncached) << " not in\n"
        << cdct;
    EXPECT_NE(cdct.find("mean PSNR along the orbits from empty caches (32², 16² faces, frames 2–3): bowl "),
              std::string::npos)
        << cdct;
}

TEST_F(DocFigures, CheckFailsWhenAGeneratedFigureIsChangedByHand) {
    const fs::path tree = copyOfTheDocs("changed");
    ASSERT_EQ(docFigures(runs(), tree).exitCode, 0);
    const fs::path performance = tree / "docs/performance.md";
    std::string text = readText(performance);
    const std::string before = block(text, "bench-grids");
    const std::size_t against = before.find(" against ");
    ASSERT_NE(against, std::string::npos) << before;
    std::string after = before;
    after.insert(against, "0");  // one more digit in the grids' time
    text.replace(text.find(before), before.size(), after);
    writeText(performance, text);
    const auto check = docFigures(runs(), tree, " --check");
    EXPECT_EQ(check.exitCode, 1) << check.out << check.err;
    EXPECT_NE(check.err.find("docs/performance.md: the block <!-- figures:bench-grids --> differs from its source"),
              std::string::npos)
        << check.err;
}

TEST_F(DocFigures, ABlockWithoutRunsStaysAsWrittenAndIsNamed) {
    // The runs of every program but grids_speed.
    const fs::path partial = dir_ / "partial-runs";
    fs::create_directories(partial);
    for (const std::string& program : programs_)
        if (program != "grids_speed") fs::copy(runs() / program, partial / program);
    const fs::path tree = copyOfTheDocs("partial");
    const std::string original = block(readText(source("docs/performance.md")), "bench-grids");
    ASSERT_FALSE(original.empty());
    for (const char* mode : {"", " --check"}) {
        const auto result = docFigures(partial, tree, mode);
        EXPECT_EQ(result.exitCode, 0) << mode << ": " << result.out << result.err;
        EXPECT_NE(result.out.find("doc-figures: not generated: no runs in " + (partial / "grids_speed").string() +
                                  " (record them: scripts/record-bench-runs.sh --programs grids_speed)"),
                  std::string::npos)
            << mode << ": " << result.out;
    }
    const std::string performance = readText(tree / "docs/performance.md");
    EXPECT_EQ(block(performance, "bench-grids"), original);
    EXPECT_NE(oneLine(block(performance, "bench-soak")).find("docs/bench-runs/soak/"), std::string::npos);
}

}  // namespace
