#include "rendercache/SamplePool.h"

#include "core/Errors.h"

namespace raycache {

void SamplePool::reset(std::size_t pixelSlotCount, std::size_t overflowCapacity) {
    const std::size_t capacity = pixelSlotCount + overflowCapacity;
    pixelSlots = pixelSlotCount;
    overflowUsed = 0;
    point.assign(capacity, SamplePoint{});
    look.assign(capacity, SampleLook{});
    reshade.assign(capacity, ReshadeInputs{});
    texturing.assign(capacity, SampleTexturing{});
}

std::size_t SamplePool::takeOverflowSlot() {
    if (used() >= capacity()) throw RuntimeError("Render Cache: no overflow slot left for a predicted sample");
    return pixelSlots + overflowUsed++;
}

}  // namespace raycache
