#include <algorithm>
#include <cstdlib>
#include <initializer_list>
#include <string>

#include "cluster/ClusterRuntime.h"

namespace raycache {

namespace {

// The first of `names` set in the environment, as a number; `fallback` if none is.
int environmentNumber(std::initializer_list<const char*> names, int fallback) {
    for (const char* name : names) {
        if (const char* value = std::getenv(name)) {
            try {
                return std::stoi(value);
            } catch (const std::exception&) {
                return fallback;
            }
        }
    }
    return fallback;
}

}  // namespace

// Open MPI's mpirun, then the PMI variables of MPICH's Hydra and of Slurm.
int launchedProcessCount() { return std::max(1, environmentNumber({"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}, 1)); }

int launchedProcessRank() { return environmentNumber({"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}, 0); }

}  // namespace raycache
