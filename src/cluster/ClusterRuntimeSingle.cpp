// ClusterRuntime in the build without MPI (RAYCACHE_MPI off): always one process.
#include <cstdlib>

#include "cluster/ClusterRuntime.h"
#include "core/Errors.h"

namespace raycache {

ClusterRuntime::ClusterRuntime(int&, char**&) {
    if (launchedProcessCount() > 1)
        throw RuntimeError("started by mpirun with " + std::to_string(launchedProcessCount()) +
                           " processes, but this raycache was built without MPI (RAYCACHE_MPI off)");
    group_ = std::make_unique<SingleProcessGroup>();
}

ClusterRuntime::~ClusterRuntime() = default;

void ClusterRuntime::abortJob(int exitCode) const { std::exit(exitCode); }

std::string ClusterRuntime::libraryVersion() { return "none (built without MPI)"; }

}  // namespace raycache
