#include "cluster/MpiProcessGroup.h"

#include <mpi.h>

#include <exception>
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

struct MpiProcessGroup::TicketWindow {
    MPI_Win window = MPI_WIN_NULL;
    std::int64_t* counter = nullptr;  // on process 0; null elsewhere
};

MpiProcessGroup::MpiProcessGroup() : tickets_(std::make_unique<TicketWindow>()) {
    // Errors are returned, not fatal, so they reach the CLI's one error line.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    // The counter lives on process 0; one passive-target epoch for the
    // group's whole life lets any process draw without process 0's help.
    const MPI_Aint bytes = rank_ == 0 ? static_cast<MPI_Aint>(sizeof(std::int64_t)) : 0;
    check(MPI_Win_allocate(bytes, sizeof(std::int64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &tickets_->counter,
                           &tickets_->window),
          "MPI_Win_allocate");
    MPI_Win_set_errhandler(tickets_->window, MPI_ERRORS_RETURN);
    if (rank_ == 0) *tickets_->counter = 0;
    // Nobody draws before process 0 has zeroed its counter.
    check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
    check(MPI_Win_lock_all(MPI_MODE_NOCHECK, tickets_->window), "MPI_Win_lock_all");
}

MpiProcessGroup::~MpiProcessGroup() {
    // MPI_Win_free is collective: while an exception unwinds (a failing
    // job, which then ends with MPI_Abort) the other processes may never
    // call it, so the window is left to MPI's end.
    if (std::uncaught_exceptions() > 0) return;
    MPI_Win_unlock_all(tickets_->window);
    MPI_Win_free(&tickets_->window);
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

void MpiProcessGroup::barrier() const { check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier"); }

std::int64_t MpiProcessGroup::drawTickets(std::int64_t count) const {
    std::int64_t before = 0;
    const std::lock_guard lock(ticketsMutex_);
    check(MPI_Fetch_and_op(&count, &before, MPI_INT64_T, 0, 0, MPI_SUM, tickets_->window), "MPI_Fetch_and_op");
    check(MPI_Win_flush(0, tickets_->window), "MPI_Win_flush");
    return before;
}

void MpiProcessGroup::resetTickets() const {
    const std::int64_t zero = 0;
    std::int64_t before = 0;
    const std::lock_guard lock(ticketsMutex_);
    check(MPI_Fetch_and_op(&zero, &before, MPI_INT64_T, 0, 0, MPI_REPLACE, tickets_->window),
          "MPI_Fetch_and_op");
    check(MPI_Win_flush(0, tickets_->window), "MPI_Win_flush");
}

void MpiProcessGroup::broadcastFromRoot(Bytes& bytes) const {
    int size = rank_ == 0 ? messageSize(bytes.size()) : 0;
    check(MPI_Bcast(&size, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
    bytes.resize(static_cast<std::size_t>(size));
    check(MPI_Bcast(bytes.data(), size, MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
}

}  // namespace raycache
