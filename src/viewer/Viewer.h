#pragma once
// `raycache view`: a window showing the ray traced frame, rendered on a
// worker thread (RenderWorker) while this thread keeps the window, the
// camera controls and the panel responsive.
#include <iosfwd>

#include "session/RenderJob.h"
#include "viewer/RenderWorker.h"
#include "viewer/ViewerOptions.h"
#include "viewer/ViewerRenderConfig.h"
#include "viewer/ViewerUiState.h"

namespace raycache {

class Viewer {
public:
    // `job` as prepared by prepareRenderJob; `config` the panel's starting values.
    Viewer(RenderJob job, const ViewerRenderConfig& config, const ViewerOptions& options);

    // Opens the window and runs until it is closed (interactive) or the
    // scripted frames are shown; progress lines of a scripted run go to
    // `out`. Throws RuntimeError when no window can be opened or rendering
    // fails, InputError for a bad screenshot path.
    void run(std::ostream& out);

private:
    // The panel's values at the start, from the options.
    ViewerUiState startingUiState() const;
    // What the render thread is made with.
    RenderWorkerSetup workerSetup(const TraceScene& tracer) const;

    RenderJob job_;
    ViewerRenderConfig config_;
    ViewerOptions options_;
};

}  // namespace raycache
