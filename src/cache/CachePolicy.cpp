#include "cache/CachePolicy.h"

#include <algorithm>

namespace raycache {

std::optional<CachePolicyMode> parseCachePolicyMode(std::string_view text) {
    if (text == "always") return CachePolicyMode::Always;
    if (text == "auto") return CachePolicyMode::Auto;
    return std::nullopt;
}

const char* cachePolicyModeName(CachePolicyMode mode) { return mode == CachePolicyMode::Auto ? "auto" : "always"; }

CubePolicy::Judgement CubePolicy::afterFrame(const CubeFrameCounts& counts) {
    if (bypassed()) {
        ++framesBypassed_;
        --bypassLeft_;  // at 0, the next frame is a probe
        return {};
    }
    ++framesCaching_;
    if (counts.tracedTrees > 0)
        meanTree_ = static_cast<double>(counts.treeRays) / static_cast<double>(counts.tracedTrees);
    Judgement j;
    j.saving = static_cast<double>(counts.hits) * std::max(meanTree_, CachePolicyCosts::kMinimumTree);
    j.cost = static_cast<double>(counts.lookups) * costs_.lookup + static_cast<double>(counts.queuedStores) * costs_.store +
             static_cast<double>(counts.cdctSteps) * costs_.cdctStep;
    // The first frame of an empty cube only fills it: its stores are an
    // investment the following frames judge.
    const bool warmUp = !warmedUp_;
    warmedUp_ = true;
    if (mode_ != CachePolicyMode::Auto || warmUp) return j;
    j.judged = true;
    if (j.cost > j.saving) {
        bypassLeft_ = backoff_;
        backoff_ = std::min(2 * backoff_, kLongestBackoff);
    } else {
        backoff_ = kFirstBackoff;
    }
    return j;
}

}  // namespace raycache
