#include "core/ScratchDirectory.h"

#include <stdlib.h>  // mkdtemp

#include <system_error>

#include "core/Errors.h"

namespace raycache {

ScratchDirectory::ScratchDirectory(const std::string& prefix) {
    std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "XXXXXX")).string();
    if (!mkdtemp(pattern.data())) throw RuntimeError("cannot create a scratch directory " + pattern);
    path_ = pattern;
}

ScratchDirectory::~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

}  // namespace raycache
