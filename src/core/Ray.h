#pragma once
#include <limits>

#include "core/Vec3.h"

namespace raycache {

// A ray segment origin + t * direction for t in [tNear, tFar].
struct Ray {
    Vec3 origin;
    Vec3 direction;
    float tNear = 0.0f;
    float tFar = std::numeric_limits<float>::infinity();
};

}  // namespace raycache
