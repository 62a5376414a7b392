#pragma once
#include "cache/CacheWorker.h"
#include "core/RayCounts.h"

namespace raycache {

// What one worker thread carries down a ray path: its ray counters and, when
// caches are in use, its cache worker (null otherwise).
struct PathContext {
    RayCounts& counts;
    CacheWorker* cache = nullptr;
};

}  // namespace raycache
