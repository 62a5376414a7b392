#include "cache/CachePolicy.h"

#include <algorithm>

namespace raycache {

const char* cachePolicyModeName(CachePolicyMode mode) { return mode == CachePolicyMode::Auto ? "auto" : "always"; }

const char* cubeStateName(CubeState state) {
    switch (state) {
    case CubeState::Sampling: return "sampling";
    case CubeState::Bypassed: return "bypassed";
    default: return "caching";
    }
}

CubePolicy::Judgement CubePolicy::afterFrame(const CubeFrameCounts& counts) {
    if (bypassed()) {
        ++framesBypassed_;
        if (--bypassLeft_ == 0) {
            // The next frame probes. A sampling cube probes over two frames:
            // one refreshes the sample from where the camera is now, the
            // next is judged, so the verdict reads frame-to-frame reuse, not
            // what the sample kept from before the bypass.
            if (samplesTexels_) {
                state_ = CubeState::Sampling;
                warmedUp_ = false;
            } else {
                state_ = CubeState::Caching;
            }
        }
        return {};
    }
    ++(sampling() ? framesSampling_ : framesCaching_);
    if (counts.tracedTrees > 0)
        meanTree_ = static_cast<double>(counts.treeRays) / static_cast<double>(counts.tracedTrees);
    Judgement j;
    // Hits are not a fair sample of the traced trees (a ray that escapes to
    // the sky is one ray, and is the likeliest to hit again), so the hits on
    // texels that recorded their trees value every hit; without them, the
    // mean of the misses' trees does.
    if (counts.recordedHits > 0)
        hitValue_ = static_cast<double>(counts.recordedHitRays) / static_cast<double>(counts.recordedHits);
    const double perHit = hitValue_ > 0.0 ? hitValue_ : std::max(meanTree_, CachePolicyCosts::kMinimumTree);
    j.saving = static_cast<double>(counts.hits) * perHit;
    j.cost = static_cast<double>(counts.lookups) * costs_.lookup + static_cast<double>(counts.queuedStores) * costs_.store +
             static_cast<double>(counts.cdctSteps) * costs_.cdctStep +
             static_cast<double>(counts.regionTests) * costs_.regionTest;
    // The first frame of an empty cube (or sample) only fills it: its stores
    // are an investment the following frames judge.
    const bool warmUp = !warmedUp_;
    warmedUp_ = true;
    if (mode_ != CachePolicyMode::Auto || warmUp) return j;
    j.judged = true;
    // A sample that pays turns full caching on, whose first frame looks up
    // every ray and stores the misses of the fifteen sixteenths of texels
    // the sample left empty: an outlay the sample's net gain must repay
    // within the first back-off, or full caching loses along the way (on
    // orbit a fill frame costs several uncached frames and nothing repays
    // it). Both at the sample's scale.
    const double fill = sampling() ? static_cast<double>(counts.lookups) *
                                         (costs_.lookup + (1.0 - kSampledShare) * costs_.store) /
                                         static_cast<double>(kFirstBackoff)
                                   : 0.0;
    if (kSavingMargin * (j.cost + fill) > j.saving) {
        state_ = CubeState::Bypassed;
        bypassLeft_ = backoff_;
        backoff_ = std::min(2 * backoff_, kLongestBackoff);
    } else {
        backoff_ = kFirstBackoff;
        if (sampling()) {
            // The sample pays: full caching, whose first frame fills the other
            // texels and is not judged.
            state_ = CubeState::Caching;
            warmedUp_ = false;
        }
    }
    return j;
}

}  // namespace raycache
