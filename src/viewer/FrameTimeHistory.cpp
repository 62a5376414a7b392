#include "viewer/FrameTimeHistory.h"

#include <algorithm>

namespace raycache {

FrameTimeHistory::FrameTimeHistory(std::size_t capacity) : times_(std::max<std::size_t>(capacity, 1)) {}

void FrameTimeHistory::add(double milliseconds) {
    times_[next_] = milliseconds;
    next_ = (next_ + 1) % times_.size();
    count_ = std::min(count_ + 1, times_.size());
}

void FrameTimeHistory::clear() {
    next_ = 0;
    count_ = 0;
}

std::vector<float> FrameTimeHistory::chronological() const {
    std::vector<float> out;
    out.reserve(count_);
    const std::size_t start = (next_ + times_.size() - count_) % times_.size();
    for (std::size_t i = 0; i < count_; ++i) out.push_back(static_cast<float>(times_[(start + i) % times_.size()]));
    return out;
}

double FrameTimeHistory::medianMs() const {
    if (count_ == 0) return 0.0;
    std::vector<float> sorted = chronological();
    const std::size_t mid = sorted.size() / 2;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(mid), sorted.end());
    double median = sorted[mid];
    if (sorted.size() % 2 == 0) {
        const float below = *std::max_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(mid));
        median = 0.5 * (median + below);
    }
    return median;
}

double FrameTimeHistory::maxMs() const {
    const std::vector<float> t = chronological();
    return t.empty() ? 0.0 : *std::max_element(t.begin(), t.end());
}

double FrameTimeHistory::fps() const {
    const double m = medianMs();
    return m > 0.0 ? 1000.0 / m : 0.0;
}

}  // namespace raycache
