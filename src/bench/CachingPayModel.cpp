#include "bench/CachingPayModel.h"

#include <limits>

namespace raycache {

double cacheableTreeMs(const CachingPayParts& parts) {
    return parts.uncachedMs - parts.idealMs + parts.idealLookupMs;
}

double cacheableShare(const CachingPayParts& parts) {
    return parts.uncachedMs > 0.0 ? cacheableTreeMs(parts) / parts.uncachedMs : 0.0;
}

double predictedFrameMs(const CachingPayParts& parts) {
    return parts.uncachedMs - parts.hitRate * cacheableTreeMs(parts) + parts.lookupMs + parts.frameEndMs;
}

double predictedSpeedup(const CachingPayParts& parts) {
    const double predicted = predictedFrameMs(parts);
    return predicted > 0.0 ? parts.uncachedMs / predicted : 0.0;
}

double freeCacheSpeedup(const CachingPayParts& parts) {
    const double rest = parts.uncachedMs - cacheableTreeMs(parts);
    if (parts.uncachedMs <= 0.0) return 0.0;
    return rest > 0.0 ? parts.uncachedMs / rest : std::numeric_limits<double>::infinity();
}

}  // namespace raycache
