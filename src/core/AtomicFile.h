#pragma once
// Writing a file so that readers only ever see the old content or the whole
// new content: write a temp file beside it, then rename over the target.
#include <filesystem>
#include <functional>
#include <string_view>

namespace raycache {

// Calls write(tempPath) to produce the file, then renames it to `path`.
// On any failure the temp file is removed and RuntimeError is thrown.
void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& tempPath)>& write);

// Convenience for text content.
void writeTextFileAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace raycache
