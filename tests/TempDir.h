#pragma once
// A fresh directory under the system temp dir, named after the running test
// (and `tag`, for a test that needs several), removed with everything in it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace raycache {

class TempDir {
public:
    explicit TempDir(const std::string& tag = "") {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = std::filesystem::temp_directory_path() /
                ("raycache-" + std::string(info->test_suite_name()) + "-" + info->name() + (tag.empty() ? "" : "-") +
                 tag);
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
