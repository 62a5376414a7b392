#pragma once
// One worker thread's view of the caches during a frame: the stores it wants
// to make (merged by RayCache::endFrame) and its counters. Owned by the frame
// renderer, one per worker, so nothing here is shared between threads.
#include <cstdint>
#include <vector>

namespace raycache {

class CacheWorker {
public:
    // Every store is ordered by (pixel, sequence within the pixel's path), a
    // key that does not depend on which thread rendered the pixel.
    void beginPixel(std::uint32_t pixelIndex) {
        pixel_ = pixelIndex;
        sequence_ = 0;
    }

private:
    friend class RayCache;

    struct PendingStore {
        std::uint64_t order;   // pixel << 24 | sequence
        std::uint32_t cube;    // index into RayCache's cubes
        std::int32_t texel;
        std::uint32_t packed;  // encoded color
        float depth;           // CDCT: distance from the cube's centre; unused by CCT
    };
    struct Counters {
        std::uint64_t lookups = 0, hits = 0, misses = 0, rejected = 0;
    };

    std::vector<PendingStore> pending_;
    std::vector<Counters> counters_;  // per cube
    std::uint32_t pixel_ = 0;
    std::uint32_t sequence_ = 0;
};

}  // namespace raycache
