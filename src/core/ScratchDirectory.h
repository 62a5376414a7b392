#pragma once
// A fresh private directory under the system's temp directory (mkdtemp),
// removed with everything in it when the object goes. For files a process
// writes only to hand them on: another process's `bench` results before they
// go to process 0, a fuzzer's inputs before a loader reads them.
#include <filesystem>
#include <string>

namespace raycache {

class ScratchDirectory {
public:
    // `prefix` begins the directory's name (e.g. "raycache-bench-"). Throws
    // RuntimeError when it cannot be created.
    explicit ScratchDirectory(const std::string& prefix);
    ~ScratchDirectory();
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

}  // namespace raycache
