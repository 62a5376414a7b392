#pragma once
// A scratch directory for one fuzzing process. The loaders under test take
// paths, not bytes, so every input is written to a file here first; the CLI
// fuzzer also points --out and --stats here, so no input can make it write
// anywhere else. The directory is removed when the process exits normally.
//
// It is ./fuzz-scratch, in the working directory, and files are named
// relative to it ("fuzz-scratch/mesh.obj"): libFuzzer learns from the strings
// the code under test compares, so a random directory name (mkdtemp) would
// make the fixed run (scripts/fuzz.sh, FUZZ_FIXED=1) mutate differently on
// every run. scripts/fuzz.sh gives each target its own working directory; two
// fuzzing processes must not share one.
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
        std::filesystem::remove_all(path());
        std::filesystem::create_directory(path());
    }
    ~FuzzScratchDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path(), ignored);
    }
    FuzzScratchDir(const FuzzScratchDir&) = delete;
    FuzzScratchDir& operator=(const FuzzScratchDir&) = delete;

    std::filesystem::path path() const { return "fuzz-scratch"; }

    // Writes `size` bytes to `name` inside the directory and returns its path.
    std::filesystem::path write(const std::string& name, const uint8_t* data, std::size_t size) const {
        const std::filesystem::path file = path() / name;
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out) throw std::runtime_error("cannot write " + file.string());
        return file;
    }

    // Empties the directory between inputs, so one input's files never feed the next.
    void clear() const {
        for (const auto& entry : std::filesystem::directory_iterator(path()))
            std::filesystem::remove_all(entry.path());
    }
};

// libFuzzer calls a plain function per input, so the directory has to outlive
// the calls: one per process, made on first use.
inline const FuzzScratchDir& fuzzScratchDir() {
    static const FuzzScratchDir dir;
    return dir;
}

}  // namespace raycache
