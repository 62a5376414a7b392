#pragma once
// `raycache render`: render a scene along a camera path, print per-frame
// timing and ray counts, write images and optional JSON statistics.
#include <iosfwd>
#include <string>

#include "app/RenderJob.h"

namespace raycache {

struct RenderCommandOptions {
    RenderJobOptions job;   // what to render, shared with the other rendering commands
    std::string out;        // image path (.png/.exr), may hold %04d; empty = no image
    std::string statsPath;  // JSON statistics; empty = none
};

// Runs the command, printing progress lines to `out`. Throws InputError for
// bad options or scene input (checked before rendering starts) and
// RuntimeError when rendering or writing fails.
void runRenderCommand(const RenderCommandOptions& options, std::ostream& out);

}  // namespace raycache
