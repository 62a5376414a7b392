#include "rendercache/SamplePool.h"

#include <algorithm>

#include "core/Errors.h"
#include "core/Parallel.h"

namespace raycache {

namespace {

// Fresh records for slots [begin, end) of every array.
void clearSlots(SamplePool& pool, std::size_t begin, std::size_t end) {
    std::fill(pool.point.begin() + begin, pool.point.begin() + end, SamplePoint{});
    std::fill(pool.look.begin() + begin, pool.look.begin() + end, SampleLook{});
    std::fill(pool.reshade.begin() + begin, pool.reshade.begin() + end, ReshadeInputs{});
    std::fill(pool.texturing.begin() + begin, pool.texturing.begin() + end, SampleTexturing{});
}

template <typename T>
void allocate(SamplePool::Records<T>& records, std::size_t capacity) {
    SamplePool::Records<T>().swap(records);  // the old memory goes first: both at once would double the peak
    records.resize(capacity);
}

}  // namespace

void SamplePool::reset(std::size_t pixelSlotCount, std::size_t overflowCapacity, const Parallel* parallel) {
    const std::size_t capacity = pixelSlotCount + overflowCapacity;
    pixelSlots = pixelSlotCount;
    overflowUsed = 0;
    allocate(point, capacity);
    allocate(look, capacity);
    allocate(reshade, capacity);
    allocate(texturing, capacity);
    // Pages are faulted in where they are first written: in chunks over the
    // workers, so that the first frame of a large image does not wait for
    // one thread to write hundreds of megabytes.
    constexpr std::size_t kChunkSlots = std::size_t{1} << 16;
    const int chunks = static_cast<int>((pixelSlotCount + kChunkSlots - 1) / kChunkSlots);
    const auto clearChunk = [&](int chunk, int) {
        const std::size_t begin = static_cast<std::size_t>(chunk) * kChunkSlots;
        clearSlots(*this, begin, std::min(pixelSlotCount, begin + kChunkSlots));
    };
    if (parallel) {
        parallel->forEachIndex(chunks, clearChunk);
    } else {
        for (int chunk = 0; chunk < chunks; ++chunk) clearChunk(chunk, 0);
    }
}

std::size_t SamplePool::takeOverflowSlot() {
    if (used() >= capacity()) throw RuntimeError("Render Cache: no overflow slot left for a predicted sample");
    const std::size_t slot = pixelSlots + overflowUsed++;
    clearSlots(*this, slot, slot + 1);
    return slot;
}

}  // namespace raycache
