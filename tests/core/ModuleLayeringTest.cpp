// The modules of src/ form layers (docs/architecture.md "Layers"): a file may
// include its own module and the modules below it, never one above. This
// test reads every source file's includes and names each one that points up,
// so a back-pointing import fails the suite instead of creeping in.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "TextPattern.h"
#include "scene/SourceTreePaths.h"

namespace raycache {
namespace {

// Bottom to top. A module may include those at or before its own place.
constexpr std::array<std::string_view, 13> kLayers = {
    "core",    // vectors, images, threads, errors
    "metrics",  // image metrics: PSNR, SSIM, heat maps
    "cluster",  // processes (MPI)
    "scene",    // scene description and loading
    "trace",    // Embree: the only module that calls it
    "cache",    // caching cubes
    "raster",   // the OpenGL G-buffer
    "render",   // the tile kernel and the ray and hybrid pipelines
    "rendercache",  // the Render Cache pipeline, built on the tile kernel
    "session",  // a render job: pipelines made by name, frames run in a loop
    "bench",    // the documents' experiments
    "viewer",   // the interactive viewer
    "app",      // the command-line commands
};

int layerOf(std::string_view module) {
    const auto it = std::find(kLayers.begin(), kLayers.end(), module);
    return it == kLayers.end() ? -1 : static_cast<int>(it - kLayers.begin());
}

TEST(ModuleLayering, EveryModuleOfSrcHasALayer) {
    const std::filesystem::path src = sourceTreeDir() / "src";
    ASSERT_TRUE(std::filesystem::is_directory(src)) << src;
    for (const auto& entry : std::filesystem::directory_iterator(src)) {
        if (!entry.is_directory()) continue;
        EXPECT_GE(layerOf(entry.path().filename().string()), 0)
            << "src/" << entry.path().filename().string() << " is not in kLayers: give it its place";
    }
}

TEST(ModuleLayering, NoIncludePointsToAHigherModule) {
    const std::filesystem::path src = sourceTreeDir() / "src";
    const test::TextPattern include(R"(^\s*#\s*include\s*"([a-z]+)/[^"]+")");
    std::vector<std::string> upward;
    std::size_t filesRead = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(src)) {
        const std::string ext = entry.path().extension().string();
        if (!entry.is_regular_file() || (ext != ".h" && ext != ".cpp")) continue;
        const std::string module = std::filesystem::relative(entry.path(), src).begin()->string();
        const int own = layerOf(module);
        if (own < 0) continue;  // reported by the test above
        ++filesRead;
        std::ifstream in(entry.path());
        std::string line;
        for (int number = 1; std::getline(in, line); ++number) {
            const std::optional<std::vector<std::string>> m = include.firstMatch(line);
            if (!m) continue;
            const std::string& included = (*m)[1];
            const int target = layerOf(included);
            if (target > own)
                upward.push_back(std::filesystem::relative(entry.path(), src).string() + ":" +
                                 std::to_string(number) + " includes " + included + "/ (above " + module + ")");
        }
    }
    EXPECT_GT(filesRead, 100u) << "the source tree was not found where expected: " << src;
    std::string list;
    for (const std::string& u : upward) list += "\n  " + u;
    EXPECT_TRUE(upward.empty()) << upward.size() << " includes point up the layers:" << list;
}

}  // namespace
}  // namespace raycache
