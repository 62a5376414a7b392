#pragma once
// An allocator whose vectors grow without writing their new elements:
// `resize(n)` only reserves the memory, so pages nobody writes are never
// faulted in. For large buffers of plain records whose readers never look
// past what was written (a pool's unused tail); everything else keeps
// std::vector's value-initialisation. Its memory comes from
// allocateLargePages(): such buffers are large.
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

#include "core/LargePages.h"

namespace raycache {

template <typename T>
struct UninitializedAllocator {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                  "only plain records may be left unwritten");
    using value_type = T;
    UninitializedAllocator() = default;
    template <typename U>
    UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) { return static_cast<T*>(allocateLargePages(n * sizeof(T))); }
    void deallocate(T* p, std::size_t) noexcept { freeLargePages(p); }
    // resize()'s new elements: left as the memory holds them.
    template <typename U>
    void construct(U*) noexcept {}
    // Copies and explicit values are written as usual.
    template <typename U, typename... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

template <typename T, typename U>
bool operator==(const UninitializedAllocator<T>&, const UninitializedAllocator<U>&) noexcept {
    return true;
}

}  // namespace raycache
