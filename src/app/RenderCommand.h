#pragma once
// `raycache render`: render a scene along a camera path, print per-frame
// timing and ray counts, write images and optional JSON statistics.
#include <iosfwd>
#include <optional>
#include <string>

namespace raycache {

struct RenderCommandOptions {
    std::string scene = "room";
    int width = 512;
    int height = 512;
    std::optional<int> frames;       // default: the scene's path length
    std::optional<std::string> path;  // static | orbit | pan; default: the scene's own path
    int threads = 0;
    int maxDepth = 6;
    float minWeight = 0.01f;
    std::optional<std::string> technique;  // none | cct; default: each material's own setting
    std::optional<int> cacheResolution;    // default: each material's own setting
    bool cacheIdeal = false;               // benchmark switch, see RayCacheSettings::ideal
    std::string out;        // image path (.png/.exr), may hold %04d; empty = no image
    std::string statsPath;  // JSON statistics; empty = none
};

// Runs the command, printing progress lines to `out`. Throws InputError for
// bad options or scene input (checked before rendering starts) and
// RuntimeError when rendering or writing fails.
void runRenderCommand(const RenderCommandOptions& options, std::ostream& out);

}  // namespace raycache
