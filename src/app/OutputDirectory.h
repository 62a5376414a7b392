#pragma once
// Output files may name directories that do not exist yet (`--out
// out/frame_%04d.png` in a fresh checkout): like most tools that write
// results, the commands create them, once the input has been checked.
#include <filesystem>

namespace raycache {

// Creates the parent directories of `file` (nothing for a bare file name).
// Throws InputError naming the directory when it cannot be created.
void createParentDirectories(const std::filesystem::path& file);

}  // namespace raycache
