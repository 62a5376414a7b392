#pragma once
// How much memory this process holds, for soak tests and benchmarks that check
// memory stays flat over many frames. Linux only (/proc, glibc).
#include <malloc.h>
#include <unistd.h>

#include <cstddef>
#include <fstream>

#if defined(__SANITIZE_ADDRESS__)
#define RAYCACHE_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RAYCACHE_ASAN 1
#endif
#endif
#ifdef RAYCACHE_ASAN
// From the sanitizer runtime (declared here: GCC does not install
// <sanitizer/allocator_interface.h>).
extern "C" std::size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace raycache {

// Resident set size in bytes (second field of /proc/self/statm, in pages); 0
// if it cannot be read. Counts every page touched: heap, mmap'd cube texels,
// thread stacks, code. Under AddressSanitizer it also holds the quarantine of
// freed blocks and shadow memory, so it grows without any leak there.
inline std::size_t residentBytes() {
    std::ifstream statm("/proc/self/statm");
    std::size_t totalPages = 0, residentPages = 0;
    if (!(statm >> totalPages >> residentPages)) return 0;
    return residentPages * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

// Bytes in live heap blocks (malloc/new, not yet freed), all threads: from the
// sanitizer's allocator under AddressSanitizer (quarantine excluded), else
// from glibc (mallinfo2: arena and mmap'd blocks in use).
inline std::size_t heapBytesInUse() {
#ifdef RAYCACHE_ASAN
    return __sanitizer_get_current_allocated_bytes();
#else
    const struct mallinfo2 info = mallinfo2();
    return info.uordblks + info.hblkhd;
#endif
}

// Whether residentBytes() measures the program rather than the sanitizer.
inline constexpr bool residentBytesAreMeaningful() {
#ifdef RAYCACHE_ASAN
    return false;
#else
    return true;
#endif
}

}  // namespace raycache
