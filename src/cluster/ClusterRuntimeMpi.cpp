// ClusterRuntime in the build with MPI (RAYCACHE_MPI on).
#include <mpi.h>

#include <cstdlib>

#include "cluster/ClusterRuntime.h"
#include "cluster/MpiProcessGroup.h"
#include "core/Errors.h"

namespace raycache {

ClusterRuntime::ClusterRuntime(int& argc, char**& argv) {
    // Not launched by mpirun: stay a plain process (MPI's singleton start
    // would cost every run, test and tool invocation for nothing).
    if (launchedProcessCount() <= 1 && !std::getenv("OMPI_COMM_WORLD_RANK")) {
        group_ = std::make_unique<SingleProcessGroup>();
        return;
    }
    // Worker threads claim tiles (MpiProcessGroup::drawTickets), one at a
    // time behind a mutex; every other call is the main thread's.
    int provided = 0;
    if (MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
        throw RuntimeError("MPI_Init_thread failed");
    if (provided < MPI_THREAD_SERIALIZED) {
        MPI_Finalize();
        throw RuntimeError("the MPI library does not allow calls from several threads (MPI_THREAD_SERIALIZED)");
    }
    initialised_ = true;
    group_ = std::make_unique<MpiProcessGroup>();
}

ClusterRuntime::~ClusterRuntime() {
    group_.reset();
    if (initialised_) MPI_Finalize();
}

void ClusterRuntime::abortJob(int exitCode) const {
    if (initialised_ && group_->size() > 1) MPI_Abort(MPI_COMM_WORLD, exitCode);
    std::exit(exitCode);
}

std::string ClusterRuntime::libraryVersion() {
    char text[MPI_MAX_LIBRARY_VERSION_STRING];
    int length = 0;
    MPI_Get_library_version(text, &length);
    std::string version(text, static_cast<std::size_t>(length));
    // "Open MPI v4.1.4, package: ..., ident: ..., repo rev: ...": the first part.
    if (const auto comma = version.find(','); comma != std::string::npos) version.resize(comma);
    return version;
}

}  // namespace raycache
