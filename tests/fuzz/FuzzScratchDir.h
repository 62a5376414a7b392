#pragma once
// A private scratch directory for one fuzzing process. The loaders under test
// take paths, not bytes, so every input is written to a file here first; the
// CLI fuzzer also points --out and --stats here, so no input can make it write
// anywhere else. The directory is removed when the process exits normally.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/ScratchDirectory.h"

namespace raycache {

class FuzzScratchDir {
public:
    FuzzScratchDir() : dir_("raycache-fuzz-") {}

    const std::filesystem::path& path() const { return dir_.path(); }

    // Writes `size` bytes to `name` inside the directory and returns its path.
    std::filesystem::path write(const std::string& name, const uint8_t* data, std::size_t size) const {
        const std::filesystem::path file = dir_.path() / name;
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out) throw std::runtime_error("cannot write " + file.string());
        return file;
    }

    // Empties the directory between inputs, so one input's files never feed the next.
    void clear() const {
        for (const auto& entry : std::filesystem::directory_iterator(dir_.path()))
            std::filesystem::remove_all(entry.path());
    }

private:
    ScratchDirectory dir_;
};

// libFuzzer calls a plain function per input, so the directory has to outlive
// the calls: one per process, made on first use.
inline const FuzzScratchDir& fuzzScratchDir() {
    static const FuzzScratchDir dir;
    return dir;
}

}  // namespace raycache
