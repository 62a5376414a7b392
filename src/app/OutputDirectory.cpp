#include "app/OutputDirectory.h"

#include <system_error>

#include "core/Errors.h"

namespace raycache {

void createParentDirectories(const std::filesystem::path& file) {
    const std::filesystem::path parent = file.parent_path();
    if (parent.empty()) return;
    std::error_code ec;
    if (std::filesystem::is_directory(parent, ec)) return;
    std::filesystem::create_directories(parent, ec);
    if (ec || !std::filesystem::is_directory(parent))
        throw InputError(InputLocation{.file = file.string()},
                         "cannot create the output directory '" + parent.string() +
                             "': " + (ec ? ec.message() : "a file of that name is in the way"));
}

}  // namespace raycache
