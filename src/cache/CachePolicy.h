#pragma once
// Whether a caching cube's lookups pay (docs/caching.md, "Caching that never
// costs"): after every frame a cube is judged from that frame's counts alone —
// what its hits saved (hits × the mean traced ray tree they replace) against
// what caching cost (lookups, queued stores, CDCT search steps) — in units of
// one traced ray. A cube that would lose steps aside: its rays are traced
// directly and nothing is looked up or stored. It probes again after a
// back-off that doubles with every probe that still loses.
//
// A CCT cube gathers its evidence on a sample: while it samples, only the
// rays whose texel lies in a fixed 1 in 16 of the cube's runs of texels are
// looked up and stored, the rest are traced as if it stood aside. Since the sample
// is chosen by texel, a sampled ray hits exactly when it would under full
// caching, so the sample's counts judge full caching at a sixteenth of its
// cost: a cube starts by sampling (one frame to fill the sample, one judged),
// and probes the same way after standing aside. Only a sample that pays
// turns full caching on; its first full frame fills the rest and is not
// judged. A CDCT lookup searches many texels, so its cubes judge full frames.
//
// Never the clock: the counts are integers summed over every worker (and every
// process), so the decision, and the image, are the same on any thread count
// and in any cluster job.
#include <array>
#include <cstdint>

namespace raycache {

enum class CachePolicyMode : unsigned char {
    Always,  // every cube caches every frame (the documents' protocol)
    Auto,    // a cube steps aside while caching would cost more than it saves
};

// Every mode, in the order messages list them.
inline constexpr std::array kCachePolicyModes{CachePolicyMode::Auto, CachePolicyMode::Always};
// "auto" / "always".
const char* cachePolicyModeName(CachePolicyMode mode);

// What one operation costs, in units of one traced ray (a secondary or shadow
// ray with the shading of its hit); ratios of CPU times, so roughly
// machine-independent. Calibrated with `scripts/calibrate-cache-policy.sh`
// (grid-32 orbit, 384², one thread) on a quiet machine, the median of three
// runs; the CDCT texel's figure carries the whole CDCT lookup: its search,
// own-surface test and error control. The tracked costs come from orbit
// (animated, 384², 256² faces, one thread). The measured times behind every
// figure are in docs/caching.md ("Calibration").
struct CachePolicyCosts {
    double lookup = 0.52;     // one lookup: address, validity, texel read
    double store = 0.94;      // one queued store: queue, merge, dependency record
    double cdctStep = 2.30;   // one texel a CDCT search sampled
    // What tracking dependencies adds in an animated scene
    // (RayCache::tracksDependencies), calibrated on orbit: a lookup's ray
    // trees bounded through the waves; a store's tree record queued and
    // merged into its block; and one test of a block's tree bounds against
    // one region a change reached (RayCache::sceneChanged), which the cube's
    // texels cost every frame of a change whether they are read or not.
    double trackedLookup = 0.25;
    double trackedStore = 2.10;
    double regionTest = 0.28;
    // The costs of a cube whose dependencies are tracked.
    CachePolicyCosts tracked() const {
        CachePolicyCosts c = *this;
        c.lookup += trackedLookup;
        c.store += trackedStore;
        return c;
    }
    // A traced tree is at least its own ray: the saving of one hit when a
    // cube has never traced one (no evidence yet) is not assumed larger.
    static constexpr double kMinimumTree = 1.0;
};

// One frame of a cube, as the policy reads it (cache/CacheStats.h).
struct CubeFrameCounts {
    std::uint64_t lookups = 0;
    std::uint64_t hits = 0;
    std::uint64_t queuedStores = 0;  // stores asked for (misses traced and handed back)
    std::uint64_t tracedTrees = 0;   // trees traced for misses whose size was counted
    std::uint64_t treeRays = 0;      // rays those trees traced, in all
    std::uint64_t cdctSteps = 0;
    // Block-against-region tests the scene change before the frame made for
    // the cube's texels; a sampling cube's scaled to the sample's share of
    // full caching (RayCache::endFrame).
    std::uint64_t regionTests = 0;
    // Of the hits of a sampling frame, those on texels that recorded the
    // tree they hold, and the rays of those trees: the mean tree a hit
    // spares, measured on the hits themselves and kept for the frames that
    // cache in full (hitValue()). Without such evidence, a hit is taken to
    // spare the mean tree the misses traced.
    std::uint64_t recordedHits = 0;
    std::uint64_t recordedHitRays = 0;
};

// What a cube does during a frame.
enum class CubeState : unsigned char {
    Caching,   // every ray leaving the object is looked up; misses are stored
    Sampling,  // only rays of sampled texels (CubePolicy::sampledTexel) are;
               // the others are traced without asking
    Bypassed,  // no ray is looked up or stored: all are traced
};
const char* cubeStateName(CubeState state);

class CubePolicy {
public:
    // Frames bypassed before the first probe, and the most between probes.
    // A sample turns full caching on only if its net gain repays, within
    // kFirstBackoff frames, the first full frame's lookups and stores.
    // A probe costs two sampled frames or one full frame for a CDCT cube
    // (docs/caching.md, "Probes").
    static constexpr int kFirstBackoff = 8;
    static constexpr int kLongestBackoff = 64;
    // The sample: 1 run of texels in 2^kSampleBits.
    static constexpr int kSampleBits = 4;
    static constexpr double kSampledShare = 1.0 / (1 << kSampleBits);
    // A cube caches only while its saving beats its cost by this factor.
    // The saving counts a hit's tree in one unit, a traced ray of grid-32,
    // but what a traced ray costs differs by scene: the factor is that
    // unit's rms error against the secondary rays' measured trace time over
    // the scenes of `bench where-caching-pays`
    // (docs/log/2026-11-27-what-a-tree-costs.md). So a cube whose hits are
    // worth 1/kSavingMargin of what the unit says still does not cache at a
    // loss (room-moving's mirror spares about half what the unit says).
    static constexpr double kSavingMargin = 1.44;

    CubePolicy() = default;
    // `samplesTexels`: whether the cube's evidence may come from a sample of
    // its texels (CCT cubes; see above). Only `auto` ever samples or bypasses.
    CubePolicy(CachePolicyMode mode, const CachePolicyCosts& costs, bool samplesTexels = false)
        : mode_(mode), costs_(costs), samplesTexels_(samplesTexels && mode == CachePolicyMode::Auto),
          state_(samplesTexels_ ? CubeState::Sampling : CubeState::Caching) {}

    // What the cube does during the coming frame.
    CubeState state() const { return state_; }
    bool bypassed() const { return state_ == CubeState::Bypassed; }
    bool sampling() const { return state_ == CubeState::Sampling; }
    // Whether texel `texel` belongs to the sample: 1 in 16 of a cube's runs of
    // 64 texels (kSampleRunBits; a multiplicative hash of the run's index).
    // Runs, not single texels: a run is one word of the validity bits and
    // four cache lines of texels, so the sampled rays, which are neighbours
    // in the image and on the cube, share the lines they read and write;
    // single scattered texels cost a cache miss per lookup and store.
    static constexpr int kSampleRunBits = 6;
    static bool sampledTexel(int texel) {
        const auto run = static_cast<std::uint32_t>(texel) >> kSampleRunBits;
        return (run * 2654435761u) >> (32 - kSampleBits) == 0;
    }
    // Whether every texel is looked up (the cube caches).
    bool admitsEveryTexel() const { return state_ == CubeState::Caching; }
    // Whether a ray addressed to `texel` is looked up (and stored) this frame.
    bool admitsTexel(int texel) const {
        return state_ == CubeState::Caching || (state_ == CubeState::Sampling && sampledTexel(texel));
    }

    // The model's figures for the frame just judged (0 for a bypassed frame).
    struct Judgement {
        double saving = 0.0;  // traced rays the hits spared
        double cost = 0.0;    // traced rays' worth of lookups, stores, searches
        bool judged = false;  // false: a bypassed frame, a warm-up frame, or `always`
    };
    // After a frame: judges it (when the cube cached it) and sets the state
    // of the next frame. `counts` are the whole frame's.
    Judgement afterFrame(const CubeFrameCounts& counts);
    // The cube was emptied (RayCache::clear): it starts over as it was made
    // (sampling, or caching, with the first back-off), and its next frame
    // fills it and is not judged. Frame counts and meanTree() stay.
    void restart() {
        state_ = samplesTexels_ ? CubeState::Sampling : CubeState::Caching;
        bypassLeft_ = 0;
        backoff_ = kFirstBackoff;
        warmedUp_ = false;
    }

    // Frames so far in each state, and the traced tree a hit replaces (mean
    // of the last frame that traced one; 0 before any).
    std::uint64_t framesCaching() const { return framesCaching_; }
    std::uint64_t framesSampling() const { return framesSampling_; }
    std::uint64_t framesBypassed() const { return framesBypassed_; }
    double meanTree() const { return meanTree_; }
    // Rays a hit spares, as the last sampling frame with recorded hits
    // measured them; 0 before any.
    double hitValue() const { return hitValue_; }
    // Frames of bypass the next losing probe would earn.
    int nextBackoff() const { return backoff_; }

private:
    CachePolicyMode mode_ = CachePolicyMode::Always;
    CachePolicyCosts costs_{};
    bool samplesTexels_ = false;
    CubeState state_ = CubeState::Caching;
    int bypassLeft_ = 0;
    int backoff_ = kFirstBackoff;
    // The cube cached (or sampled) a frame since it was built, emptied,
    // turned to full caching, or came back from standing aside to sample.
    bool warmedUp_ = false;
    double meanTree_ = 0.0;
    double hitValue_ = 0.0;
    std::uint64_t framesCaching_ = 0, framesSampling_ = 0, framesBypassed_ = 0;
};

}  // namespace raycache
