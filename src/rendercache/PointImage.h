#pragma once
// The reprojected samples as an image (Walter et al. 1999): at most one sample per
// pixel, the nearest, over the image plus a margin past each edge where
// samples are kept though not shown. A pixel holds only its sample's depth:
// the sample itself sits in the pixel's own slot of the sample pool
// (pixelIndex), so the image needs no slot. Four bytes per pixel: the
// depth test reads and writes the image once per sample, and its size is
// what that costs.
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

namespace raycache {

class PointImage {
public:
    // width x height pixels plus `margin` on each side, all without a sample.
    void reset(int width, int height, int margin);

    int width() const { return width_; }
    int height() const { return height_; }
    int margin() const { return margin_; }
    // Whether pixel (x, y) lies in the image or its margin.
    bool covers(int x, int y) const {
        return x >= -margin_ && y >= -margin_ && x < width_ + margin_ && y < height_ + margin_;
    }

    // The depth test, for a caller that makes sure no other thread touches
    // pixel (x, y) meanwhile (no atomic instruction, which cost more than
    // the projection when every sample made one): `offered` (a key()) wins
    // the pixel if it is smaller than the key the pixel holds. An equal key
    // does not: the caller, who knows which samples the two are, breaks the
    // tie. `held` gets the key the pixel held (emptyKey() if none). Returns
    // whether the offer won.
    bool offerUnshared(int x, int y, std::uint32_t offered, std::uint32_t& held) {
        std::uint32_t& current = keys_[index(x, y)];
        held = current;
        if (offered >= held) return false;
        current = offered;
        return true;
    }
    // Puts a sample at depth `depth` at pixel (x, y) unconditionally (a
    // freshly traced sample).
    void place(int x, int y, float depth) { keys_[index(x, y)] = key(depth); }
    // Writes key `k` at pixel (x, y) (the depth test's own marks removed).
    void setKey(int x, int y, std::uint32_t k) { keys_[index(x, y)] = k; }
    // Removes whatever sample pixel (x, y) holds.
    void clear(int x, int y) { keys_[index(x, y)] = kEmptyKey; }

    // The key of pixel (x, y): the bits of its sample's depth. Positive
    // floats (+infinity included) order as their bit patterns do, so
    // smaller is nearer; no sample is the largest value.
    // `nearerThan(d)` is the largest key nearer than d.
    std::uint32_t keyAt(int x, int y) const { return keys_[index(x, y)]; }
    static std::uint32_t key(float depth) { return std::bit_cast<std::uint32_t>(depth); }
    static std::uint32_t nearerThan(float depth) { return key(depth) - 1; }
    static constexpr std::uint32_t emptyKey() { return kEmptyKey; }
    static float depthOf(std::uint32_t k) { return std::bit_cast<float>(k); }

    // Pixel (x, y) numbered row by row over the image and its margin, from
    // 0 at (-margin, -margin): the sample pool's slot of the pixel.
    std::size_t pixelIndex(int x, int y) const { return index(x, y); }
    // Pixels in a row and rows, margin included.
    int stride() const { return stride_; }
    int rows() const { return height_ + 2 * margin_; }
    std::size_t pixelCount() const { return keys_.size(); }

    // The keys, pixelIndex() order, for loops that keep the address in a
    // register (through the member the compiler reloads it after every store
    // it cannot tell apart from one into this object).
    std::uint32_t* keyData() { return keys_.data(); }
    const std::uint32_t* keyData() const { return keys_.data(); }

    float depthAt(int x, int y) const { return depthOf(keys_[index(x, y)]); }
    bool hasSample(int x, int y) const { return keys_[index(x, y)] != kEmptyKey; }

private:
    static constexpr std::uint32_t kEmptyKey = std::numeric_limits<std::uint32_t>::max();
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y + margin_) * static_cast<std::size_t>(stride_) +
               static_cast<std::size_t>(x + margin_);
    }

    int width_ = 0, height_ = 0, margin_ = 0, stride_ = 0;
    std::vector<std::uint32_t> keys_;
};

}  // namespace raycache
