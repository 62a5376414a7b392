#pragma once
// Test helper: the processes of a cluster job simulated by threads of one
// process, exchanging through shared memory, so the distributed frame's
// logic (tile assignment, store exchange, gather) runs in-process and under
// the sanitizers, without MPI. One hub per job; one group per thread.
#include <algorithm>
#include <barrier>
#include <functional>
#include <thread>
#include <vector>

#include "core/ProcessGroup.h"

namespace raycache {

class ThreadProcessHub {
public:
    explicit ThreadProcessHub(int size) : size_(size), barrier_(size), slots_(static_cast<std::size_t>(size)) {}
    int size() const { return size_; }

private:
    friend class ThreadProcessGroup;
    int size_;
    std::barrier<> barrier_;
    std::vector<Bytes> slots_;
    LocalTicketCounter tickets_;
};

class ThreadProcessGroup final : public ProcessGroup {
public:
    ThreadProcessGroup(ThreadProcessHub& hub, int rank) : hub_(hub), rank_(rank) {}
    int rank() const override { return rank_; }
    int size() const override { return hub_.size(); }
    void allGather(std::span<const std::byte> local, GatheredBytes& into) const override {
        hub_.slots_[static_cast<std::size_t>(rank_)].assign(local.begin(), local.end());
        hub_.barrier_.arrive_and_wait();
        std::vector<std::size_t> sizes;
        for (const Bytes& slot : hub_.slots_) sizes.push_back(slot.size());
        std::byte* out = into.reset(std::span<const std::size_t>(sizes));
        for (const Bytes& slot : hub_.slots_) out = std::copy(slot.begin(), slot.end(), out);
        hub_.barrier_.arrive_and_wait();  // nobody writes a slot before everyone has read them
    }
    void gatherToRoot(std::span<const std::byte> local, GatheredBytes& into) const override {
        allGather(local, into);
        if (!isRoot()) into.clear();
    }
    void broadcastFromRoot(Bytes& bytes) const override {
        if (isRoot()) hub_.slots_[0] = bytes;
        hub_.barrier_.arrive_and_wait();
        if (!isRoot()) bytes = hub_.slots_[0];
        hub_.barrier_.arrive_and_wait();
    }
    void barrier() const override { hub_.barrier_.arrive_and_wait(); }
    std::int64_t drawTickets(std::int64_t count) const override { return hub_.tickets_.draw(count); }
    void resetTickets() const override { hub_.tickets_.reset(); }

private:
    ThreadProcessHub& hub_;
    int rank_;
};

// Runs body(group) on `processes` threads, one simulated process each, and
// waits for them.
inline void runAsProcesses(int processes, const std::function<void(const ProcessGroup&)>& body) {
    ThreadProcessHub hub(processes);
    std::vector<std::thread> threads;
    for (int r = 0; r < processes; ++r)
        threads.emplace_back([&hub, &body, r] {
            const ThreadProcessGroup group(hub, r);
            body(group);
        });
    for (std::thread& t : threads) t.join();
}

}  // namespace raycache
