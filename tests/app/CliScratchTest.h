#pragma once
// A fixture for tests that run the raycache binary (RAYCACHE_BINARY, set by
// the test target): a scratch directory per test, named after the test and
// removed afterwards, and run(args), whose stderr passes through it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>

#include "TempDir.h"
#include "ShellRun.h"

namespace raycache::test {

class CliScratchTest : public ::testing::Test {
protected:
    // `prefix` starts the scratch directory's name under the system's temporary directory.
    explicit CliScratchTest(std::string prefix) : prefix_(std::move(prefix)) {}

    void SetUp() override {
        dir_ = ::raycache::scratchPathForThisTest(prefix_);
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    // `raycache <args>` as a shell runs it.
    RunResult run(const std::string& args) const {
        return runShell(std::string(RAYCACHE_BINARY) + " " + args, dir_ / "stderr.txt");
    }

    std::filesystem::path dir_;

private:
    std::string prefix_;
};

}  // namespace raycache::test
