#pragma once
// A private scratch directory for one fuzzing process. The loaders under test
// take paths, not bytes, so every input is written to a file here first; the
// CLI fuzzer also points --out and --stats here, so no input can make it write
// anywhere else. The directory is removed when the process exits normally.
#include <stdlib.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace raycache {

class FuzzScratchDir {
public:
    FuzzScratchDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "raycache-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a scratch directory");
        dir_ = pattern;
    }
    ~FuzzScratchDir() {
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }
    FuzzScratchDir(const FuzzScratchDir&) = delete;
    FuzzScratchDir& operator=(const FuzzScratchDir&) = delete;

    const std::filesystem::path& path() const { return dir_; }

    // Writes `size` bytes to `name` inside the directory and returns its path.
    std::filesystem::path write(const std::string& name, const uint8_t* data, std::size_t size) const {
        const std::filesystem::path file = dir_ / name;
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out) throw std::runtime_error("cannot write " + file.string());
        return file;
    }

    // Empties the directory between inputs, so one input's files never feed the next.
    void clear() const {
        for (const auto& entry : std::filesystem::directory_iterator(dir_)) std::filesystem::remove_all(entry.path());
    }

private:
    std::filesystem::path dir_;
};

// libFuzzer calls a plain function per input, so the directory has to outlive
// the calls: one per process, made on first use.
inline const FuzzScratchDir& fuzzScratchDir() {
    static const FuzzScratchDir dir;
    return dir;
}

}  // namespace raycache
