#pragma once
// ProcessGroup over MPI_COMM_WORLD (Open MPI). MPI must be initialised for
// the group's lifetime (cluster/ClusterRuntime.h does that).
#include <memory>
#include <mutex>

#include "core/ProcessGroup.h"

namespace raycache {

class MpiProcessGroup final : public ProcessGroup {
public:
    // Collective (it creates the window holding the ticket counters).
    MpiProcessGroup();
    ~MpiProcessGroup() override;
    MpiProcessGroup(const MpiProcessGroup&) = delete;
    MpiProcessGroup& operator=(const MpiProcessGroup&) = delete;
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    void allGather(std::span<const std::byte> local, GatheredBytes& into) const override;
    void gatherToRoot(std::span<const std::byte> local, GatheredBytes& into) const override;
    void broadcastFromRoot(Bytes& bytes) const override;
    void barrier() const override;
    // One-sided atomics on process 0's window (MPI_Fetch_and_op), serialised
    // within this process: MPI runs at MPI_THREAD_SERIALIZED.
    std::int64_t drawTickets(std::int64_t count) const override;
    void resetTickets() const override;

private:
    struct TicketWindow;
    int rank_ = 0;
    int size_ = 1;
    std::unique_ptr<TicketWindow> tickets_;
    mutable std::mutex ticketsMutex_;
};

}  // namespace raycache
