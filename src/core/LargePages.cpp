#include "core/LargePages.h"

#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace raycache {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
}

void* allocateLargePages(std::size_t bytes) {
    if (bytes < kHugePage) {
        void* memory = std::malloc(bytes == 0 ? 1 : bytes);
        if (!memory) throw std::bad_alloc();
        return memory;
    }
    const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* memory = std::aligned_alloc(kHugePage, rounded);
    if (!memory) throw std::bad_alloc();
    madvise(memory, rounded, MADV_HUGEPAGE);  // advice only: where the kernel has none to give, it is ignored
    return memory;
}

void freeLargePages(void* memory) noexcept {
    std::free(memory);
}

}  // namespace raycache
