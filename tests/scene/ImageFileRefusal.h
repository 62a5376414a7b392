#pragma once
// The check every refused image file gets: an InputError whose location and
// one-line message name the file, and whose message says why.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/Errors.h"
#include "scene/ImageLoader.h"

namespace raycache {

inline void expectImageFileRefused(const std::filesystem::path& path, const std::string& detail = "") {
    try {
        loadImageFile(path);
        FAIL() << "no exception for " << path;
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.where().file, path.string());
        EXPECT_NE(what.find(path.string()), std::string::npos) << what;
        EXPECT_NE(what.find(detail), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

}  // namespace raycache
