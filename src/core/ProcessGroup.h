#pragma once
// The processes of one job (an MPI job: src/cluster/MpiProcessGroup), as the
// renderer sees them: a few collective byte exchanges. The renderer only
// talks to this interface, so the build without MPI renders the same code
// with SingleProcessGroup. Every call is collective: every process of the
// group must make the same calls in the same order.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace raycache {

using Bytes = std::vector<std::byte>;

// Every process's bytes after a gather, back to back in one buffer. Kept by
// the caller from frame to frame: a frame gathers megabytes, and a fresh
// buffer each time costs the page faults of touching it (docs/cluster.md,
// "Where the time goes").
class GatheredBytes {
public:
    // How many processes' parts it holds (0 on a process that received none).
    std::size_t count() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }
    std::span<const std::byte> of(std::size_t rank) const {
        return std::span<const std::byte>(all_).subspan(offsets_.at(rank), offsets_.at(rank + 1) - offsets_.at(rank));
    }

    // For the exchanges: room for parts of `sizes` bytes, in rank order; returns
    // where part 0 starts. The buffer's capacity is kept.
    template <typename Size>
    std::byte* reset(std::span<const Size> sizes) {
        offsets_.assign(1, 0);
        for (const Size size : sizes) offsets_.push_back(offsets_.back() + static_cast<std::size_t>(size));
        all_.resize(offsets_.back());
        return all_.data();
    }
    void clear() { offsets_.clear(); }

private:
    Bytes all_;
    std::vector<std::size_t> offsets_;
};

class ProcessGroup {
public:
    virtual ~ProcessGroup() = default;

    // This process's index in [0, size()); process 0 writes the outputs.
    virtual int rank() const = 0;
    virtual int size() const = 0;
    bool isRoot() const { return rank() == 0; }

    // Every process's `local`, indexed by rank, into `into` on every process.
    virtual void allGather(std::span<const std::byte> local, GatheredBytes& into) const = 0;
    // Every process's `local`, indexed by rank, into `into` on process 0;
    // `into` is emptied elsewhere.
    virtual void gatherToRoot(std::span<const std::byte> local, GatheredBytes& into) const = 0;
    // Process 0's `bytes` on every process (in place).
    virtual void broadcastFromRoot(Bytes& bytes) const = 0;
    // Returns once every process has called it.
    virtual void barrier() const = 0;

    // Work sharing without a collective: process 0 holds a counter, 0 at
    // the start, from which any thread of any process may draw at any time
    // without the other processes taking part (the tiles claimed by
    // TileBalance::Claim). Returns the counter's value before `count` was added.
    virtual std::int64_t drawTickets(std::int64_t count) const = 0;
    // Sets the counter back to 0; process 0 only. The caller makes sure that
    // no process draws meanwhile (barriers before and after).
    virtual void resetTickets() const = 0;
};

// The ticket counter in this process's memory, for the groups whose
// processes share it (one process; processes simulated by threads in tests).
// Relaxed: the tickets order nothing else, the collectives around them do.
class LocalTicketCounter {
public:
    std::int64_t draw(std::int64_t count) { return counter_.fetch_add(count, std::memory_order_relaxed); }
    void reset() { counter_.store(0, std::memory_order_relaxed); }

private:
    std::atomic<std::int64_t> counter_{0};
};

// A group of one: every exchange returns the process's own bytes.
class SingleProcessGroup final : public ProcessGroup {
public:
    int rank() const override { return 0; }
    int size() const override { return 1; }
    void allGather(std::span<const std::byte> local, GatheredBytes& into) const override {
        const std::size_t size = local.size();
        std::byte* out = into.reset(std::span<const std::size_t>(&size, 1));
        if (size != 0) std::memcpy(out, local.data(), size);
    }
    void gatherToRoot(std::span<const std::byte> local, GatheredBytes& into) const override { allGather(local, into); }
    void broadcastFromRoot(Bytes&) const override {}
    void barrier() const override {}
    std::int64_t drawTickets(std::int64_t count) const override { return tickets_.draw(count); }
    void resetTickets() const override { tickets_.reset(); }

private:
    mutable LocalTicketCounter tickets_;
};

// Plain values to and from bytes, for the exchanges above (same binary on
// every process, so no byte-order conversion).
template <typename T>
void appendBytes(Bytes& out, std::span<const T> values) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (values.empty()) return;
    const std::size_t at = out.size();
    out.resize(at + values.size_bytes());
    std::memcpy(out.data() + at, values.data(), values.size_bytes());
}
template <typename T>
void appendBytes(Bytes& out, const T& value) {
    appendBytes(out, std::span<const T>(&value, 1));
}

// Reads values written by appendBytes in order; throws std::out_of_range
// when the bytes run out (a malformed message).
class ByteReader {
public:
    explicit ByteReader(std::span<const std::byte> bytes) : bytes_(bytes) {}
    template <typename T>
    T read() {
        T value;
        readInto(std::span<T>(&value, 1));
        return value;
    }
    template <typename T>
    void readInto(std::span<T> values) {
        static_assert(std::is_trivially_copyable_v<T>);
        if (values.size_bytes() > bytes_.size() - offset_) throw std::out_of_range("truncated process message");
        if (values.empty()) return;
        std::memcpy(values.data(), bytes_.data() + offset_, values.size_bytes());
        offset_ += values.size_bytes();
    }
    bool atEnd() const { return offset_ == bytes_.size(); }

private:
    std::span<const std::byte> bytes_;
    std::size_t offset_ = 0;
};

}  // namespace raycache
