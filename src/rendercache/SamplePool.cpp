#include "rendercache/SamplePool.h"

#include "core/Errors.h"

namespace raycache {

void SamplePool::reset(std::size_t pixelSlotCount, std::size_t overflowCapacity) {
    const std::size_t capacity = pixelSlotCount + overflowCapacity;
    pixelSlots = pixelSlotCount;
    overflowUsed = 0;
    objectId.assign(capacity, kEmpty);
    position.assign(capacity, Vec3{});
    color.assign(capacity, Rgb{});
    age.assign(capacity, 0);
    viewDependent.assign(capacity, 0);
    primitiveId.assign(capacity, 0);
    baryU.assign(capacity, 0.0f);
    baryV.assign(capacity, 0.0f);
    viewIndependent.assign(capacity, Rgb{});
    litMask.assign(capacity, 0);
}

std::size_t SamplePool::takeOverflowSlot() {
    if (used() >= capacity()) throw RuntimeError("Render Cache: no overflow slot left for a predicted sample");
    return pixelSlots + overflowUsed++;
}

}  // namespace raycache
