#pragma once
// `raycache cache-view`: render a scene's camera path with caching, then
// write one object's caching cube unfolded as a cross (cache/CubeCross.h),
// to see what the cube holds and where it is still invalid.
#include <iosfwd>
#include <string>

#include "session/RenderJob.h"

namespace raycache {

struct CacheViewCommandOptions {
    RenderJobOptions job;  // what to render, shared with `render`
    std::string object;    // name of the object whose cube is shown
    std::string out;       // the cross image (.png/.exr)
    std::string show = "color";  // color | depth (CDCT cubes)
};

// Runs the command, printing one progress line per frame and, at the end, the
// cube's invalid texels and memory to `out`. Throws InputError (before
// rendering) for bad options, scene input, an unknown object or one without a
// cache, and RuntimeError when rendering or writing fails. What loading the
// scene repaired goes to `notes`, one "note: …" line each.
void runCacheViewCommand(const CacheViewCommandOptions& options, std::ostream& out, std::ostream& notes);

}  // namespace raycache
