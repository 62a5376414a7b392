#pragma once
// Six square faces around one object, one RGB9E5 word per texel, holding the
// color that secondary rays leaving the object in each direction brought back
// (CCT, SPEC §2). Texels start invalid and are written once.
#include <cstddef>
#include <cstdint>
#include <optional>

#include "cache/CubeAddressing.h"
#include "core/Rgb.h"
#include "core/TexelBuffer.h"
#include "core/Vec3.h"

namespace raycache {

class CachingCube {
public:
    // `size` texels per face side; every texel invalid.
    CachingCube(const Vec3& center, int size);

    const Vec3& center() const { return center_; }
    int size() const { return size_; }
    std::size_t texelCount() const { return texels_.size(); }
    std::size_t validCount() const { return validCount_; }
    std::size_t bytes() const { return texels_.size() * sizeof(std::uint32_t); }

    // Texel index addressed by a direction from the centre.
    int texelIndexFor(const Vec3& direction) const {
        return cubeTexelIndex(cubeTexelFromDirection(direction, size_), size_);
    }
    // The cached color at `index`, or nothing if the texel is invalid.
    std::optional<Rgb> read(int index) const {
        const std::uint32_t packed = texels_[static_cast<std::size_t>(index)];
        if (packed == kInvalidTexel) return std::nullopt;
        return decodeTexel(packed);
    }
    bool isValid(int index) const { return texels_[static_cast<std::size_t>(index)] != kInvalidTexel; }
    // Writes `packed` if the texel is still invalid; returns whether it wrote.
    bool writeIfInvalid(int index, std::uint32_t packed);
    // Marks every texel invalid again.
    void clear();

    // Raw texel words, face-major (see cubeTexelIndex); for views and tests.
    std::span<const std::uint32_t> texels() const { return texels_.words(); }

    static std::uint32_t encodeTexel(const Rgb& color);
    static Rgb decodeTexel(std::uint32_t packed);
    static const std::uint32_t kInvalidTexel;

private:
    Vec3 center_;
    int size_;
    TexelBuffer texels_;
    std::size_t validCount_ = 0;
};

}  // namespace raycache
