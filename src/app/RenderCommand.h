#pragma once
// `raycache render`: render a scene along a camera path, print per-frame
// timing and ray counts, write images and optional JSON statistics.
#include <iosfwd>
#include <string>

#include "core/ProcessGroup.h"
#include "session/RenderJob.h"

namespace raycache {

struct RenderCommandOptions {
    RenderJobOptions job;   // what to render, shared with the other rendering commands
    std::string out;        // image path (.png/.exr), may hold %04d; empty = no image
    std::string statsPath;  // JSON statistics; empty = none
};

// Runs the command, printing progress lines to `out` and what loading the
// scene repaired (Scene::notes) as "note: …" lines to `notes`. Throws InputError for
// bad options or scene input (checked before rendering starts) and
// RuntimeError when rendering or writing fails.
//
// With a `group` of several processes (an MPI job, docs/cluster.md) every
// process runs this with the same options: the frames' tiles are shared
// among them (or, with caches off and several frames, whole frames), and
// only process 0 prints to `out` and `notes` and writes files. Input that fails on any
// process throws ProcessGroupFailure (core/ProcessAgreement.h) on all of them
// before anything is rendered.
void runRenderCommand(const RenderCommandOptions& options, std::ostream& out, std::ostream& notes,
                      const ProcessGroup& group = SingleProcessGroup{});

}  // namespace raycache
