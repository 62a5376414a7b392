// keepFreedMemoryInProcess(): a frame-sized block comes from the heap, not a
// mapping of its own, and freeing it does not hand the heap back.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "core/FreedMemory.h"

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#include <malloc.h>
#define RAYCACHE_GLIBC_MALLOC 1
#endif

using namespace raycache;

TEST(FreedMemory, AFrameSizedBlockComesFromTheHeapAndStaysWithTheProcess) {
#if defined(RAYCACHE_GLIBC_MALLOC)
    keepFreedMemoryInProcess();
    const struct mallinfo2 before = mallinfo2();
    constexpr std::size_t kBlock = std::size_t{8} << 20;  // a 1024² image of floats, twice
    void* block = std::malloc(kBlock);
    ASSERT_NE(block, nullptr);
    std::memset(block, 1, kBlock);
    const struct mallinfo2 held = mallinfo2();
    EXPECT_EQ(held.hblks, before.hblks) << "the block was mapped on its own";
    std::free(block);
    const struct mallinfo2 after = mallinfo2();
    EXPECT_GE(after.arena, held.arena) << "the heap was given back when the block was freed";
#else
    GTEST_SKIP() << "malloc is not glibc's here (a sanitizer's, or another C library)";
#endif
}
