#include "core/TexelBuffer.h"

#include <algorithm>

#include "core/LargePages.h"

namespace raycache {

namespace {
std::uint32_t* allocateWords(std::size_t count) {
    return static_cast<std::uint32_t*>(allocateLargePages(count * sizeof(std::uint32_t)));
}
}  // namespace

void TexelBuffer::Free::operator()(std::uint32_t* p) const {
    freeLargePages(p);
}

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

void TexelBuffer::fill(std::uint32_t value) {
    std::fill_n(data_.get(), count_, value);
}

}  // namespace raycache
