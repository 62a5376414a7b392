#pragma once
// The last N frame times, for the panel's frame-time graph and fps figure.
#include <cstddef>
#include <vector>

namespace raycache {

class FrameTimeHistory {
public:
    explicit FrameTimeHistory(std::size_t capacity = 240);

    void add(double milliseconds);
    void clear();

    std::size_t size() const { return count_; }
    // Oldest first, as the graph plots them.
    std::vector<float> chronological() const;
    // Median of the stored times; 0 when empty.
    double medianMs() const;
    double maxMs() const;
    // 1000 / median; 0 when empty.
    double fps() const;

private:
    std::vector<double> times_;
    std::size_t next_ = 0;
    std::size_t count_ = 0;
};

}  // namespace raycache
