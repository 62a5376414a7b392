#include "core/TexelBuffer.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdlib>
#include <new>

namespace raycache {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::uint32_t* allocateWords(std::size_t count) {
    const std::size_t bytes = std::max<std::size_t>(1, count * sizeof(std::uint32_t));
    // Huge-page alignment only pays for buffers of at least one huge page.
    const std::size_t alignment = bytes >= kHugePage ? kHugePage : alignof(std::max_align_t);
    const std::size_t rounded = (bytes + alignment - 1) / alignment * alignment;
    void* p = std::aligned_alloc(alignment, rounded);
    if (!p) throw std::bad_alloc();
    if (alignment == kHugePage) madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure is harmless
    return static_cast<std::uint32_t*>(p);
}
}  // namespace

void TexelBuffer::Free::operator()(std::uint32_t* p) const { std::free(p); }

TexelBuffer::TexelBuffer(std::size_t count, std::uint32_t value) : data_(allocateWords(count)), count_(count) {
    fill(value);
}

TexelBuffer::TexelBuffer(const TexelBuffer& other) : data_(allocateWords(other.count_)), count_(other.count_) {
    std::copy_n(other.data_.get(), count_, data_.get());
}

TexelBuffer& TexelBuffer::operator=(const TexelBuffer& other) {
    if (this != &other) *this = TexelBuffer(other);
    return *this;
}

void TexelBuffer::fill(std::uint32_t value) { std::fill_n(data_.get(), count_, value); }

}  // namespace raycache
