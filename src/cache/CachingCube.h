#pragma once
// Six square faces around one object, one RGB9E5 word per texel, holding the
// color that secondary rays leaving the object in each direction brought back
// (CCT, Ruff, Clua and Fernandes 2013). Texels start invalid and are written once.
// A CDCT cube (Ruff's MSc thesis, 2013) also keeps, per texel, the distance from the centre to
// what the texel shows (a 32-bit float, -1 while invalid), and has a box: the
// axis-aligned bounds of the object around the centre, where its search starts.
// A CCT cube may be resampled to another resolution (resampled()); a texel
// that got its colour from a coarser texel is valid but inherited: it answers
// only lookups whose footprint allows a texel that much wider, and the next
// store to it replaces it (docs/caching.md, "Resolution from the view").
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "cache/CubeAddressing.h"
#include "core/Rgb.h"
#include "core/TexelBuffer.h"
#include "core/Vec3.h"

namespace raycache {

class CachingCube {
public:
    static constexpr float kInvalidDepth = -1.0f;

    // A color-only (CCT) cube with `size` texels per face side; every texel invalid.
    CachingCube(const Vec3& center, int size);
    // A color-and-depth (CDCT) cube whose box spans center ± halfSize (every
    // component > 0); every texel invalid.
    CachingCube(const Vec3& center, int size, const Vec3& halfSize);

    const Vec3& center() const { return center_; }
    int size() const { return size_; }
    bool hasDepth() const { return depths_.has_value(); }
    // Half the box's extent per axis (CDCT cubes only; zero for CCT cubes).
    const Vec3& halfSize() const { return halfSize_; }
    std::size_t texelCount() const { return texels_.size(); }
    std::size_t validCount() const { return validCount_; }
    std::size_t bytes() const {
        return texels_.size() * sizeof(std::uint32_t) * (depths_ ? 2u : 1u) + inherited_.size();
    }

    // Texel index addressed by a direction from the centre.
    int texelIndexFor(const Vec3& direction) const {
        return cubeTexelIndex(cubeTexelFromDirection(direction, size_), size_);
    }
    // The cached color at `index`, or nothing if the texel is invalid.
    std::optional<Rgb> read(int index) const {
        if (!isValid(index)) return std::nullopt;
        return decodeTexel(texels_[static_cast<std::size_t>(index)]);
    }
    // Answered from a bit per texel (1/32 of the texels' memory), so asking
    // about an invalid texel never touches the large texel array.
    bool isValid(int index) const {
        const auto i = static_cast<std::size_t>(index);
        return (validBits_[i >> 6] >> (i & 63)) & 1u;
    }
    // Where the validity bit and the texel word of `index` live, for callers
    // that prefetch a batch of lookups before reading them.
    const std::uint64_t* validWordOf(int index) const { return &validBits_[static_cast<std::size_t>(index) >> 6]; }
    const std::uint32_t* texelWordOf(int index) const { return &texels_[static_cast<std::size_t>(index)]; }
    // The decoded color of a texel known to be valid.
    Rgb readValid(int index) const { return decodeTexel(texels_[static_cast<std::size_t>(index)]); }
    // The stored distance from the centre at `index` (CDCT cubes), kInvalidDepth if invalid.
    float depth(int index) const { return std::bit_cast<float>((*depths_)[static_cast<std::size_t>(index)]); }
    // How many levels coarser the texel that gave valid texel `index` its
    // colour was (0: a store into this texel itself).
    int inheritedLevels(int index) const {
        return inherited_.empty() ? 0 : inherited_[static_cast<std::size_t>(index)];
    }
    // Whether any texel may be inherited (false: inheritedLevels is 0 everywhere).
    bool mayInherit() const { return !inherited_.empty(); }
    // Writes `packed` (and, in a CDCT cube, `depth`) if the texel is still
    // invalid or only inherited; returns whether it wrote.
    bool writeIfInvalid(int index, std::uint32_t packed, float depth = kInvalidDepth);
    // Marks texel `index` invalid again; returns whether it was valid.
    bool invalidate(int index);
    // Marks every texel invalid again.
    void clear();
    // This CCT cube at `size` texels per face side, `size` = size() * 2^k or
    // size() / 2^k (k >= 0). Going finer, each texel inherits the colour of
    // the texel it lies in (k levels more inherited). Going coarser, each
    // texel takes the least inherited valid texel under it (the first in
    // row order among equals), k levels less inherited, never below 0: a
    // stored ray's direction lies within every coarser texel over its own.
    // `sourceOf` (optional): per new texel, the texel it came from, -1 if none.
    // Throws std::logic_error for a CDCT cube or another ratio.
    CachingCube resampled(int size, std::vector<int>* sourceOf = nullptr) const;
    // Moves the cube with its object (the box keeps its size); texels keep
    // what they hold.
    void moveTo(const Vec3& center) { center_ = center; }

    // Raw texel words, face-major (see cubeTexelIndex); for views and tests.
    std::span<const std::uint32_t> texels() const { return texels_.words(); }
    // Raw depth words (float bits), same order; empty for CCT cubes.
    std::span<const std::uint32_t> depthWords() const {
        return depths_ ? depths_->words() : std::span<const std::uint32_t>{};
    }

    static std::uint32_t encodeTexel(const Rgb& color);
    static Rgb decodeTexel(std::uint32_t packed);
    static const std::uint32_t kInvalidTexel;

private:
    Vec3 center_;
    int size_;
    Vec3 halfSize_{};
    TexelBuffer texels_;
    std::optional<TexelBuffer> depths_;
    std::vector<std::uint64_t> validBits_;  // bit i: texel i valid
    std::size_t validCount_ = 0;
    // Per texel, inheritedLevels(); empty while no texel is inherited.
    std::vector<std::uint8_t> inherited_;
};

}  // namespace raycache
