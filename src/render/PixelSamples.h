#pragma once
// Where in its pixel each of a pixel's `--spp N` camera rays passes: a fixed
// sequence of stratified jitter (docs/usage.md, "Anti-aliasing"). The pixel
// is cut into a grid of cols x rows strata (cols = ceil(sqrt N), rows =
// ceil(N / cols)); sample s lies in stratum (s mod cols, s / cols), at a
// place inside it drawn from a hash of (x, y, s). The same pixel and sample
// give the same place on every run, thread count and machine.
#include <cmath>
#include <cstdint>

namespace raycache {

// A sample's place in its pixel: offsets in [0, 1) from the pixel's top-left
// corner, x to the right and y down (as pixel rows count).
struct PixelOffset {
    float x = 0.5f, y = 0.5f;
};

class PixelSamples {
public:
    explicit PixelSamples(int count)
        : count_(count), cols_(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))))),
          rows_((count + cols_ - 1) / cols_) {}

    int count() const { return count_; }

    PixelOffset offset(int x, int y, int sample) const {
        const std::uint32_t key = hash(static_cast<std::uint32_t>(x) * 0x9E3779B1u ^
                                       hash(static_cast<std::uint32_t>(y) * 0x85EBCA77u ^
                                            hash(static_cast<std::uint32_t>(sample) + 0x27D4EB2Fu)));
        const float u = unit(hash(key)), v = unit(hash(key ^ 0x68E31DA4u));
        const int col = sample % cols_, row = sample / cols_;
        return {(static_cast<float>(col) + u) / static_cast<float>(cols_),
                (static_cast<float>(row) + v) / static_cast<float>(rows_)};
    }

private:
    // Chris Wellons' "lowbias32" integer hash (hash-prospector).
    static std::uint32_t hash(std::uint32_t h) {
        h ^= h >> 16;
        h *= 0x7FEB352Du;
        h ^= h >> 15;
        h *= 0x846CA68Bu;
        h ^= h >> 16;
        return h;
    }
    // The top 24 bits as a float in [0, 1).
    static float unit(std::uint32_t h) { return static_cast<float>(h >> 8) * 0x1.0p-24f; }

    int count_, cols_, rows_;
};

}  // namespace raycache
