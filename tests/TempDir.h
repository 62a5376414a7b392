#pragma once
// A fresh directory under the system temp dir, named after the running test
// (and `tag`, for a test that needs several), removed with everything in it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace raycache {

// A path under the system temp dir for the running test: `prefix`, the test's
// name, then the process id, so that two suites running at once (release and
// asan, or two checkouts) never share a directory.
inline std::filesystem::path scratchPathForThisTest(const std::string& prefix) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    return std::filesystem::temp_directory_path() /
           (prefix + info->name() + "-" + std::to_string(static_cast<long>(getpid())));
}

class TempDir {
public:
    explicit TempDir(const std::string& tag = "") {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = scratchPathForThisTest("raycache-" + std::string(info->test_suite_name()) + "-" +
                                       (tag.empty() ? "" : tag + "-"));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

}  // namespace raycache
