#include "cache/CachingCube.h"

#include "core/SharedExponentColor.h"

namespace raycache {

const std::uint32_t CachingCube::kInvalidTexel = SharedExponentColor::kInvalid;

CachingCube::CachingCube(const Vec3& center, int size)
    : center_(center), size_(size), texels_(6u * static_cast<std::size_t>(size) * static_cast<std::size_t>(size),
                                            kInvalidTexel) {}

bool CachingCube::writeIfInvalid(int index, std::uint32_t packed) {
    std::uint32_t& texel = texels_[static_cast<std::size_t>(index)];
    if (texel != kInvalidTexel) return false;
    texel = packed;
    ++validCount_;
    return true;
}

void CachingCube::clear() {
    texels_.fill(kInvalidTexel);
    validCount_ = 0;
}

std::uint32_t CachingCube::encodeTexel(const Rgb& color) { return SharedExponentColor::encode(color); }
Rgb CachingCube::decodeTexel(std::uint32_t packed) { return SharedExponentColor::decode(packed); }

}  // namespace raycache
