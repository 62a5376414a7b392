#include "cache/CoarseLevels.h"

#include <algorithm>
#include <cmath>

namespace raycache {

namespace {

int sizeAtLevel(int finestSize, int level) { return (finestSize + (1 << level) - 1) >> level; }

}  // namespace

CoarseLevels::CoarseLevels(const Vec3& center, int finestSize, int levels) : finestSize_(finestSize) {
    for (int k = 1; k < std::min(levels, kMaxLevels) && sizeAtLevel(finestSize, k) >= kMinSize; ++k) {
        levels_.emplace_back(center, sizeAtLevel(finestSize, k));
        seen_.emplace_back(levels_.back().texelCount());
    }
}

int CoarseLevels::coarsestAllowed(float spread, float errorBound, int finestSize, int levelCount) {
    // Level k's texels span 2^(k+1) / n radians: allowed while 2^k <= bound * spread * n / 2.
    const float widest = errorBound * spread * static_cast<float>(finestSize) * 0.5f;
    if (!(widest >= 2.0f)) return 0;  // also NaN
    const int k = std::isfinite(widest) ? static_cast<int>(std::floor(std::log2(widest))) : kMaxLevels;
    return std::clamp(k, 0, levelCount - 1);
}

bool CoarseLevels::seesWithin(const SeenPoint& seen, const Vec3& origin, const Vec3& direction, float maxAngle) {
    return seesWithinTangent(seen, origin, direction, std::tan(std::clamp(maxAngle, 0.0f, 1.5f)));
}

int CoarseLevels::texelOver(int finestTexel, int level) const {
    const int n = finestSize_;
    return texelOver(finestTexel / (n * n), finestTexel % n, (finestTexel / n) % n, level);
}

int CoarseLevels::writeOver(int finestTexel, std::uint32_t packed, const SeenPoint& seen) {
    const int n = finestSize_;
    const int face = finestTexel / (n * n), y = (finestTexel / n) % n, x = finestTexel % n;
    int written = 0;
    for (int k = 1; k < levelCount(); ++k) {
        const int t = texelOver(face, x, y, k);
        if (!levels_[static_cast<std::size_t>(k - 1)].writeIfInvalid(t, packed)) continue;
        seen_[static_cast<std::size_t>(k - 1)][static_cast<std::size_t>(t)] = seen;
        ++written;
    }
    return written;
}

std::int64_t CoarseLevels::dropOver(int face, int x0, int y0, int x1, int y1) {
    std::int64_t dropped = 0;
    for (int k = 1; k < levelCount(); ++k) {
        CachingCube& cube = levels_[static_cast<std::size_t>(k - 1)];
        const int size = cube.size();
        for (int y = y0 >> k; y <= (y1 - 1) >> k; ++y)
            for (int x = x0 >> k; x <= (x1 - 1) >> k; ++x) {
                dropped += cube.invalidate((face * size + y) * size + x) ? 1 : 0;
            }
    }
    return dropped;
}

void CoarseLevels::clear() {
    for (CachingCube& cube : levels_) cube.clear();
}

void CoarseLevels::moveTo(const Vec3& center) {
    for (CachingCube& cube : levels_) cube.moveTo(center);
}

std::size_t CoarseLevels::bytes() const {
    std::size_t total = 0;
    for (const CachingCube& cube : levels_) total += cube.bytes() + cube.texelCount() * sizeof(SeenPoint);
    return total;
}

std::size_t CoarseLevels::validCount() const {
    std::size_t total = 0;
    for (const CachingCube& cube : levels_) total += cube.validCount();
    return total;
}

}  // namespace raycache
