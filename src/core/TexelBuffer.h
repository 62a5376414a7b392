#pragma once
// A fixed-size array of 32-bit words for large, randomly accessed tables
// (caching cubes: tens to hundreds of MiB read at scattered texels). It asks
// the kernel for transparent huge pages (core/LargePages.h).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

namespace raycache {

class TexelBuffer {
public:
    TexelBuffer(std::size_t count, std::uint32_t fill);
    TexelBuffer(const TexelBuffer& other);
    TexelBuffer& operator=(const TexelBuffer& other);
    TexelBuffer(TexelBuffer&&) noexcept = default;
    TexelBuffer& operator=(TexelBuffer&&) noexcept = default;

    std::size_t size() const { return count_; }
    std::uint32_t& operator[](std::size_t i) { return data_[i]; }
    const std::uint32_t& operator[](std::size_t i) const { return data_[i]; }
    std::span<const std::uint32_t> words() const { return {data_.get(), count_}; }
    void fill(std::uint32_t value);

private:
    struct Free {
        void operator()(std::uint32_t* p) const;
    };
    std::unique_ptr<std::uint32_t[], Free> data_;
    std::size_t count_ = 0;
};

}  // namespace raycache
