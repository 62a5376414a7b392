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
    const auto put = [&](std::size_t n, int source, int inherited) {
        if (!out.isValid(static_cast<int>(n))) {
            out.validBits_[n >> 6] |= std::uint64_t{1} << (n & 63);
            ++out.validCount_;
        }
        out.texels_[n] = texels_[static_cast<std::size_t>(source)];
        out.inherited_[n] = static_cast<std::uint8_t>(inherited);
        if (sourceOf) (*sourceOf)[n] = source;
    };
    // Going coarser: per new texel, the inherited level of the old texel it took.
    std::vector<std::int16_t> taken(finer ? 0 : out.texels_.size(), 256);
    // Only valid texels matter, and most cubes are resized while still
    // sparse: walk the validity words, skipping 64 empty texels at a time,
    // in increasing index order (face, row, column).
    for (std::size_t word = 0; word < validBits_.size(); ++word)
        for (std::uint64_t bits = validBits_[word]; bits != 0; bits &= bits - 1) {
            const int t = static_cast<int>(word * 64 + static_cast<std::size_t>(std::countr_zero(bits)));
            const int face = t / (from * from), y = (t / from) % from, x = t % from;
            if (finer) {
                // Every texel under it inherits it.
                const int inherited = std::min(inheritedLevels(t) + levels, 255);
                for (int j = 0; j < ratio; ++j)
                    for (int i = 0; i < ratio; ++i)
                        put(static_cast<std::size_t>((face * size + y * ratio + j) * size + x * ratio + i), t, inherited);
            } else {
                // The texel over it keeps the least inherited of its valid
                // texels; among equals the first in row order, which is the
                // first met in index order.
                const auto n = static_cast<std::size_t>((face * size + y / ratio) * size + x / ratio);
                const int own = inheritedLevels(t);
                if (own >= taken[n]) continue;
                taken[n] = static_cast<std::int16_t>(own);
                put(n, t, std::max(own - levels, 0));
            }
        }
    if (std::none_of(out.inherited_.begin(), out.inherited_.end(), [](std::uint8_t v) { return v != 0; }))
        out.inherited_.clear();
    return out;
}

std::uint32_t CachingCube::encodeTexel(const Rgb& color) { return SharedExponentColor::encode(color); }
Rgb CachingCube::decodeTexel(std::uint32_t packed) { return SharedExponentColor::decode(packed); }

}  // namespace raycache
