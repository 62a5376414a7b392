#include "core/FreedMemory.h"

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace raycache {

void keepFreedMemoryInProcess() {
#if defined(__GLIBC__)
    // glibc's ceiling for the threshold on 64-bit systems: larger values are refused.
    constexpr int kLargestMmapThreshold = 32 * 1024 * 1024;
    mallopt(M_MMAP_THRESHOLD, kLargestMmapThreshold);
    // Never give the heap's free top back to the system, and grow it in
    // large steps: while a path's first frames still grow it, small steps
    // fault fresh pages in frame after frame.
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    mallopt(M_TOP_PAD, 64 * 1024 * 1024);
#endif
}

}  // namespace raycache
