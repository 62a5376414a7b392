#pragma once
// How the process keeps the memory it frees. By default glibc hands blocks
// of 128 KiB and more back to the system when they are freed (munmap, or a
// trimmed heap), so a program that allocates a large buffer every frame
// takes fresh pages every frame; on the virtual machines this project runs
// on, each page fault is costly and the passes that run next find their
// caches and TLB cold (`bench render-cache`'s per-frame image metrics slowed
// the Render Cache passes it timed:
// docs/log/2026-11-29-render-cache-folds-and-lanes.md).
namespace raycache {

// Blocks up to glibc's largest mmap threshold (32 MiB) come from the heap,
// the heap grows 64 MiB at a time, and freed memory stays with the process
// for the next allocation. A no-op where the C library is not glibc. Call
// once, first thing in main().
void keepFreedMemoryInProcess();

}  // namespace raycache
