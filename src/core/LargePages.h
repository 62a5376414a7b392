#pragma once
// Memory for large buffers that are read at scattered places or touched
// first all at once (caching cubes, the Render Cache's sample pools): a
// block of at least one huge page is aligned to one and advised to the
// kernel as such, so that one fault brings in 2 MiB instead of 4 KiB and
// scattered reads miss the TLB far less.
#include <cstddef>

namespace raycache {

// `bytes` of memory (at least one byte's worth); throws std::bad_alloc.
void* allocateLargePages(std::size_t bytes);
void freeLargePages(void* memory) noexcept;

}  // namespace raycache
