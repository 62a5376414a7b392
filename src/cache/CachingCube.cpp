#include "cache/CachingCube.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

#include "core/SharedExponentColor.h"

namespace raycache {

const std::uint32_t CachingCube::kInvalidTexel = SharedExponentColor::kInvalid;

CachingCube::CachingCube(const Vec3& center, int size)
    : center_(center), size_(size), texels_(6u * static_cast<std::size_t>(size) * static_cast<std::size_t>(size),
                                            kInvalidTexel),
      validBits_((texels_.size() + 63) / 64, 0) {}

CachingCube::CachingCube(const Vec3& center, int size, const Vec3& halfSize) : CachingCube(center, size) {
    halfSize_ = halfSize;
    depths_.emplace(texels_.size(), std::bit_cast<std::uint32_t>(kInvalidDepth));
}

bool CachingCube::writeIfInvalid(int index, std::uint32_t packed, float depth) {
    const auto i = static_cast<std::size_t>(index);
    if (isValid(index)) {
        if (inherited_.empty() || inherited_[i] == 0) return false;
        inherited_[i] = 0;  // an inherited colour gives way to the texel's own
        texels_[i] = packed;
        return true;
    }
    validBits_[i >> 6] |= std::uint64_t{1} << (i & 63);
    texels_[i] = packed;
    if (depths_) (*depths_)[static_cast<std::size_t>(index)] = std::bit_cast<std::uint32_t>(depth);
    ++validCount_;
    return true;
}

bool CachingCube::invalidate(int index) {
    if (!isValid(index)) return false;
    const auto i = static_cast<std::size_t>(index);
    validBits_[i >> 6] &= ~(std::uint64_t{1} << (i & 63));
    texels_[i] = kInvalidTexel;
    if (depths_) (*depths_)[i] = std::bit_cast<std::uint32_t>(kInvalidDepth);
    --validCount_;
    if (!inherited_.empty()) inherited_[i] = 0;
    return true;
}

void CachingCube::clear() {
    texels_.fill(kInvalidTexel);
    std::fill(validBits_.begin(), validBits_.end(), 0);
    if (depths_) depths_->fill(std::bit_cast<std::uint32_t>(kInvalidDepth));
    validCount_ = 0;
    inherited_.clear();
}

CachingCube CachingCube::resampled(int size, std::vector<int>* sourceOf) const {
    if (depths_) throw std::logic_error("CachingCube::resampled: a CDCT cube keeps its resolution");
    const int from = size_;
    const bool finer = size >= from;
    const int ratio = finer ? size / from : from / size;
    if (size <= 0 || ratio < 1 || (ratio & (ratio - 1)) != 0 || (finer ? from * ratio : size * ratio) != (finer ? size : from))
        throw std::logic_error("CachingCube::resampled: " + std::to_string(from) + " to " + std::to_string(size) +
                               " is not a power-of-two step");
    const int levels = std::countr_zero(static_cast<unsigned>(ratio));
    CachingCube out(center_, size);
    out.inherited_.assign(out.texels_.size(), 0);
    if (sourceOf) sourceOf->assign(out.texels_.size(), -1);
    const auto oldIndex = [&](int face, int x, int y) { return (face * from + y) * from + x; };
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                int source = -1, inherited = 0;
                if (finer) {
                    source = oldIndex(face, x / ratio, y / ratio);
                    if (!isValid(source)) continue;
                    inherited = std::min(inheritedLevels(source) + levels, 255);
                } else {
                    int best = 256;
                    for (int j = 0; j < ratio; ++j)
                        for (int i = 0; i < ratio; ++i) {
                            const int t = oldIndex(face, x * ratio + i, y * ratio + j);
                            if (isValid(t) && inheritedLevels(t) < best) {
                                best = inheritedLevels(t);
                                source = t;
                            }
                        }
                    if (source < 0) continue;
                    inherited = std::max(best - levels, 0);
                }
                const auto n = static_cast<std::size_t>((face * size + y) * size + x);
                out.validBits_[n >> 6] |= std::uint64_t{1} << (n & 63);
                out.texels_[n] = texels_[static_cast<std::size_t>(source)];
                out.inherited_[n] = static_cast<std::uint8_t>(inherited);
                ++out.validCount_;
                if (sourceOf) (*sourceOf)[n] = source;
            }
    if (std::none_of(out.inherited_.begin(), out.inherited_.end(), [](std::uint8_t v) { return v != 0; }))
        out.inherited_.clear();
    return out;
}

std::uint32_t CachingCube::encodeTexel(const Rgb& color) { return SharedExponentColor::encode(color); }
Rgb CachingCube::decodeTexel(std::uint32_t packed) { return SharedExponentColor::decode(packed); }

}  // namespace raycache
