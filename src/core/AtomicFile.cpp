#include "core/AtomicFile.h"

#include <unistd.h>

#include <fstream>

#include "core/Errors.h"

namespace raycache {

void writeFileAtomically(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path&)>& write) {
    const std::filesystem::path temp =
        path.parent_path() / ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()));
    try {
        write(temp);
        std::filesystem::rename(temp, path);
    } catch (const std::exception& e) {
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        throw RuntimeError("cannot write " + path.string() + ": " + e.what());
    }
}

void writeTextFileAtomically(const std::filesystem::path& path, std::string_view text) {
    writeFileAtomically(path, [&](const std::filesystem::path& temp) {
        std::ofstream out(temp, std::ios::binary);
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        out.close();
        if (!out) throw RuntimeError("write failed");
    });
}

}  // namespace raycache
