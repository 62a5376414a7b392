#pragma once
// The process's place in a cluster job: when started by an MPI launcher
// (mpirun), MPI is initialised for the object's lifetime and group() spans
// the job's processes; otherwise (or in a build without MPI, RAYCACHE_MPI
// off) group() is this process alone and MPI is never touched, so a plain
// `raycache render` pays nothing for it. Made once, by main().
#include <memory>
#include <string>

#include "core/ProcessGroup.h"

namespace raycache {

class ClusterRuntime {
public:
    // Throws RuntimeError when started by an MPI launcher with several
    // processes but built without MPI (every process would render the whole
    // job and write the same files).
    ClusterRuntime(int& argc, char**& argv);
    ~ClusterRuntime();
    ClusterRuntime(const ClusterRuntime&) = delete;
    ClusterRuntime& operator=(const ClusterRuntime&) = delete;

    const ProcessGroup& group() const { return *group_; }

    // Ends every process of the job with `exitCode`, now: for a failure on
    // one process that the others cannot learn of (they would wait for it
    // forever). With one process, std::exit.
    [[noreturn]] void abortJob(int exitCode) const;

    // "Open MPI 4.1.4", or "none (built without MPI)", for reports.
    static std::string libraryVersion();

private:
    std::unique_ptr<ProcessGroup> group_;
    bool initialised_ = false;
};

// How many processes the MPI launcher that started this process started
// (1 when not launched by one), and this one's rank among them (0 when not):
// read from the launcher's environment, before (or without) MPI.
int launchedProcessCount();
int launchedProcessRank();

}  // namespace raycache
