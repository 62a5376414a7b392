#pragma once
// Where the tests find the source tree (tests/data, examples, the fetched
// meshes) and the raycache program: from the test program's own place, by
// paths relative to it that tests/CMakeLists.txt works out
// (RAYCACHE_TEST_DATA_DIR, RAYCACHE_SOURCE_DIR, RAYCACHE_BINARY call this).
// Relative, so that the compile command is the same in every clone and the
// compiler cache serves a fresh clone the objects of another.
#include <filesystem>
#include <string>

namespace raycache::test {

inline std::string pathFromTestProgram(const char* relative) {
    static const std::filesystem::path programDir = std::filesystem::read_symlink("/proc/self/exe").parent_path();
    std::filesystem::path p = (programDir / relative).lexically_normal();
    if (!p.has_filename()) p = p.parent_path();  // "a/b/" from a path ending in ".."
    return p.string();
}

}  // namespace raycache::test
