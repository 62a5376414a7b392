#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

#include "ScopedEnvironment.h"
#include "TempDir.h"
#include "ThreadProcessGroup.h"
#include "app/BenchCommand.h"

namespace raycache {
namespace {

std::set<std::filesystem::path> scratchDirectories() {
    std::set<std::filesystem::path> dirs;
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::temp_directory_path()))
        if (entry.path().filename().string().starts_with("raycache-bench-")) dirs.insert(entry.path());
    return dirs;
}

// `raycache bench` over 2 processes (simulated by threads): the experiments
// are dealt over both, and process 0 ends up with every experiment's
// results as one process would, while the other process's scratch
// directory is gone.
TEST(DistributedBench, EveryExperimentsResultsReachProcessZero) {
    TempDir dir;
    // Scratch directories go under TMPDIR: a private one, so that tests
    // running beside this one (ctest -j) cannot add or remove directories
    // while it counts them; given back when the test ends, as the directory
    // goes with `dir`.
    const std::filesystem::path privateTemp = dir.path() / "tmp";
    std::filesystem::create_directories(privateTemp);
    const test::ScopedEnvironment temp("TMPDIR", privateTemp.string());
    ASSERT_EQ(std::filesystem::temp_directory_path(), privateTemp);
    const std::set<std::filesystem::path> scratchBefore = scratchDirectories();
    BenchCommandOptions options;
    options.experiments = {"table-5.3", "fill-rate", "quality"};
    options.tiny = true;
    options.threads = 1;
    options.outDir = dir.path().string();
    std::ostringstream rootOut;
    runAsProcesses(2, [&](const ProcessGroup& group) {
        std::ostringstream discarded;  // what raycache's main does with the other processes' output
        runBenchCommand(options, group.isRoot() ? static_cast<std::ostream&>(rootOut) : discarded, group);
    });
    for (const std::string& name : options.experiments) {
        EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / name / "results.md")) << name;
        EXPECT_TRUE(std::filesystem::is_regular_file(dir.path() / name / "results.json")) << name;
    }
    const std::string printed = rootOut.str();
    EXPECT_NE(printed.find("over 2 processes"), std::string::npos) << printed;
    // The experiments are dealt by estimated work: process 1 ran at least one.
    EXPECT_NE(printed.find("(process 1)"), std::string::npos) << printed;
    EXPECT_EQ(scratchDirectories(), scratchBefore);
}

// An unknown experiment stops every process together with the same error.
TEST(DistributedBench, UnknownExperimentStopsEveryProcess) {
    TempDir dir;
    BenchCommandOptions options;
    options.experiments = {"no-such-experiment"};
    options.tiny = true;
    options.outDir = dir.path().string();
    std::mutex mutex;
    int failures = 0;
    runAsProcesses(2, [&](const ProcessGroup& group) {
        std::ostringstream out;
        try {
            runBenchCommand(options, out, group);
        } catch (const std::exception& e) {
            const std::lock_guard lock(mutex);
            EXPECT_NE(std::string(e.what()).find("no-such-experiment"), std::string::npos) << e.what();
            ++failures;
        }
    });
    EXPECT_EQ(failures, 2);
}

}  // namespace
}  // namespace raycache
