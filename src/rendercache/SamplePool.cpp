#include "rendercache/SamplePool.h"

namespace raycache {

void SamplePool::reset(std::size_t capacity) {
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

}  // namespace raycache
