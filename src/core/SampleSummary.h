#pragma once
// Median and range of a set of timings: how every speed figure is reported.
#include <span>

namespace raycache {

struct SampleSummary {
    double median = 0.0;
    double min = 0.0;
    double max = 0.0;
};

// All zero for an empty set; the median of an even count is the mean of the middle two.
SampleSummary summarize(std::span<const double> samples);

}  // namespace raycache
