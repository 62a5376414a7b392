#include "cache/CachingCube.h"

#include <algorithm>

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
    if (isValid(index)) return false;
    const auto i = static_cast<std::size_t>(index);
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
    return true;
}

void CachingCube::clear() {
    texels_.fill(kInvalidTexel);
    std::fill(validBits_.begin(), validBits_.end(), 0);
    if (depths_) depths_->fill(std::bit_cast<std::uint32_t>(kInvalidDepth));
    validCount_ = 0;
}

std::uint32_t CachingCube::encodeTexel(const Rgb& color) { return SharedExponentColor::encode(color); }
Rgb CachingCube::decodeTexel(std::uint32_t packed) { return SharedExponentColor::decode(packed); }

}  // namespace raycache
