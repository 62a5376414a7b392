#include "cluster/MpiProcessGroup.h"

#include <mpi.h>

#include <limits>

#include "core/Errors.h"

namespace raycache {

namespace {

// MPI counts are ints: a message of 2 GiB or more cannot be sent in one call.
int messageSize(std::size_t bytes) {
    if (bytes > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw RuntimeError("a message between MPI processes of " + std::to_string(bytes) +
                           " bytes is larger than MPI's 2 GiB limit");
    return static_cast<int>(bytes);
}

void check(int code, const char* what) {
    if (code == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw RuntimeError(std::string(what) + ": " + std::string(text, static_cast<std::size_t>(length)));
}

// Displacements of the parts with `sizes`, and their total.
std::vector<int> offsetsOf(const std::vector<int>& sizes, std::size_t& total) {
    std::vector<int> offsets(sizes.size());
    total = 0;
    for (std::size_t r = 0; r < sizes.size(); ++r) {
        offsets[r] = messageSize(total);
        total += static_cast<std::size_t>(sizes[r]);
    }
    messageSize(total);
    return offsets;
}

}  // namespace

MpiProcessGroup::MpiProcessGroup() {
    // Errors are returned, not fatal, so they reach the CLI's one error line.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

void MpiProcessGroup::allGather(std::span<const std::byte> local, GatheredBytes& into) const {
    const int mine = messageSize(local.size());
    std::vector<int> sizes(static_cast<std::size_t>(size_));
    check(MPI_Allgather(&mine, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
    std::size_t total = 0;
    const std::vector<int> offsets = offsetsOf(sizes, total);
    std::byte* all = into.reset(std::span<const int>(sizes));
    check(MPI_Allgatherv(local.data(), mine, MPI_BYTE, all, sizes.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD),
          "MPI_Allgatherv");
}

void MpiProcessGroup::gatherToRoot(std::span<const std::byte> local, GatheredBytes& into) const {
    const int mine = messageSize(local.size());
    std::vector<int> sizes(static_cast<std::size_t>(size_));
    check(MPI_Gather(&mine, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
    if (rank_ != 0) {
        into.clear();
        check(MPI_Gatherv(local.data(), mine, MPI_BYTE, nullptr, nullptr, nullptr, MPI_BYTE, 0, MPI_COMM_WORLD),
              "MPI_Gatherv");
        return;
    }
    std::size_t total = 0;
    const std::vector<int> offsets = offsetsOf(sizes, total);
    std::byte* all = into.reset(std::span<const int>(sizes));
    check(MPI_Gatherv(local.data(), mine, MPI_BYTE, all, sizes.data(), offsets.data(), MPI_BYTE, 0, MPI_COMM_WORLD),
          "MPI_Gatherv");
}

void MpiProcessGroup::broadcastFromRoot(Bytes& bytes) const {
    int size = rank_ == 0 ? messageSize(bytes.size()) : 0;
    check(MPI_Bcast(&size, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
    bytes.resize(static_cast<std::size_t>(size));
    check(MPI_Bcast(bytes.data(), size, MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
}

}  // namespace raycache
