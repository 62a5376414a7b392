#include "core/SampleSummary.h"

#include <algorithm>
#include <vector>

namespace raycache {

SampleSummary summarize(std::span<const double> samples) {
    if (samples.empty()) return {};
    std::vector<double> v(samples.begin(), samples.end());
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    const double median = n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    return {median, v.front(), v.back()};
}

}  // namespace raycache
