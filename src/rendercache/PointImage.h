#pragma once
// The reprojected samples as an image (SPEC §6): at most one sample per
// pixel, the nearest, over the image plus a margin past each edge where
// samples are kept though not shown. Reprojection offers samples from many
// threads; which one wins a pixel depends only on depth, ties going to the
// lower slot, never on thread timing.
#include <atomic>
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

namespace raycache {

class PointImage {
public:
    static constexpr std::uint32_t kNoSample = std::numeric_limits<std::uint32_t>::max();

    // width x height pixels plus `margin` on each side, all without a sample.
    void reset(int width, int height, int margin);

    int width() const { return width_; }
    int height() const { return height_; }
    int margin() const { return margin_; }
    // Whether pixel (x, y) lies in the image or its margin.
    bool covers(int x, int y) const {
        return x >= -margin_ && y >= -margin_ && x < width_ + margin_ && y < height_ + margin_;
    }

    // Offers sample `slot` at depth `depth` (> 0) to pixel (x, y), which
    // `covers` must hold for. Safe to call from many threads at once.
    void offer(int x, int y, float depth, std::uint32_t slot) {
        std::atomic_ref<std::uint64_t> key(keys_[index(x, y)]);
        const std::uint64_t offered = pack(depth, slot);
        std::uint64_t current = key.load(std::memory_order_relaxed);
        while (offered < current && !key.compare_exchange_weak(current, offered, std::memory_order_relaxed)) {
        }
    }
    // offer() for a caller that makes sure no other thread touches pixel
    // (x, y) meanwhile: no atomic instruction, which cost more than the
    // projection when every sample made one. `key` as key(depth, slot).
    // Returns the key that lost: the one the pixel held if the offer is
    // nearer, else the offer; emptyKey() if the pixel held none.
    std::uint64_t offerUnshared(int x, int y, std::uint64_t key) {
        std::uint64_t& current = keys_[index(x, y)];
        const std::uint64_t held = current;
        if (key >= held) return key;
        current = key;
        return held;
    }
    // Puts `slot` at pixel (x, y) unconditionally (a freshly traced sample).
    void place(int x, int y, float depth, std::uint32_t slot) { keys_[index(x, y)] = pack(depth, slot); }
    // Removes whatever sample pixel (x, y) holds.
    void clear(int x, int y) { keys_[index(x, y)] = kEmptyKey; }

    // The packed (depth, slot) of pixel (x, y): smaller is nearer, no sample
    // is the largest value. `nearerThan(d)` is the largest key nearer than d.
    std::uint64_t keyAt(int x, int y) const { return keys_[index(x, y)]; }
    static std::uint64_t nearerThan(float depth) { return pack(depth, 0) - 1; }
    static constexpr std::uint64_t emptyKey() { return kEmptyKey; }
    // The key offer(x, y, depth, slot) competes with, and its parts.
    static std::uint64_t key(float depth, std::uint32_t slot) { return pack(depth, slot); }
    static std::uint32_t slotOf(std::uint64_t key) { return static_cast<std::uint32_t>(key); }
    static float depthOf(std::uint64_t key) { return std::bit_cast<float>(static_cast<std::uint32_t>(key >> 32)); }

    // Pixel (x, y) numbered row by row over the image and its margin, from
    // 0 at (-margin, -margin): the sample pool's slot of the pixel.
    std::size_t pixelIndex(int x, int y) const { return index(x, y); }
    // Pixels in a row and rows, margin included.
    int stride() const { return stride_; }
    int rows() const { return height_ + 2 * margin_; }
    std::size_t pixelCount() const { return keys_.size(); }

    std::uint32_t slotAt(int x, int y) const { return static_cast<std::uint32_t>(keys_[index(x, y)]); }
    float depthAt(int x, int y) const { return depthOf(keys_[index(x, y)]); }
    bool hasSample(int x, int y) const { return keys_[index(x, y)] != kEmptyKey; }

private:
    static constexpr std::uint64_t kEmptyKey = std::numeric_limits<std::uint64_t>::max();
    // Positive floats order as their bit patterns do: depth in the high half
    // makes the nearest sample the smallest key, the slot breaks ties.
    static std::uint64_t pack(float depth, std::uint32_t slot) {
        return std::uint64_t{std::bit_cast<std::uint32_t>(depth)} << 32 | slot;
    }
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(y + margin_) * static_cast<std::size_t>(stride_) +
               static_cast<std::size_t>(x + margin_);
    }

    int width_ = 0, height_ = 0, margin_ = 0, stride_ = 0;
    std::vector<std::uint64_t> keys_;
};

}  // namespace raycache
