#pragma once
// ProcessGroup over MPI_COMM_WORLD (Open MPI). MPI must be initialised for
// the group's lifetime (cluster/ClusterRuntime.h does that).
#include "core/ProcessGroup.h"

namespace raycache {

class MpiProcessGroup final : public ProcessGroup {
public:
    MpiProcessGroup();
    int rank() const override { return rank_; }
    int size() const override { return size_; }
    void allGather(std::span<const std::byte> local, GatheredBytes& into) const override;
    void gatherToRoot(std::span<const std::byte> local, GatheredBytes& into) const override;
    void broadcastFromRoot(Bytes& bytes) const override;

private:
    int rank_ = 0;
    int size_ = 1;
};

}  // namespace raycache
