#include "rendercache/ReshadeBudget.h"

#include <algorithm>
#include <cmath>

#include "render/RenderCacheSettings.h"

namespace raycache {

int reshadeIntervalWithin(double budgetMs, int interval, double reshadeMs) {
    if (!(budgetMs > 0.0)) return 1;
    interval = std::clamp(interval, 1, kMaxReshadeInterval);
    if (!(reshadeMs > 0.0)) return interval;  // nothing measured: keep
    const double everySample = reshadeMs * interval;
    const double wanted = std::ceil(everySample / budgetMs);
    if (wanted > interval) return static_cast<int>(std::min<double>(wanted, kMaxReshadeInterval));
    if (interval > 1 && everySample / (interval - 1) <= 0.75 * budgetMs) return interval - 1;
    return interval;
}

}  // namespace raycache
