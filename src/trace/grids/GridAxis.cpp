#include "trace/grids/GridAxis.h"

#include <cmath>

namespace raycache {

void GridAxis::setUniform(double lo, double hi, int count) {
    count_ = count;
    lastCell_ = count - 1;
    angular_ = false;
    const double step = (hi - lo) / count;
    bounds_.resize(static_cast<std::size_t>(count) + 1);
    for (int i = 0; i < count; ++i) bounds_[static_cast<std::size_t>(i)] = lo + i * step;
    bounds_.back() = hi;
    estimateOrigin_ = lo;
    estimateScale_ = 1.0 / step;
    step_ = step;
}

void GridAxis::setAngular(double angleLo, double angleHi, int count) {
    count_ = count;
    lastCell_ = count - 1;
    angular_ = true;
    const double step = (angleHi - angleLo) / count;
    bounds_.resize(static_cast<std::size_t>(count) + 1);
    for (int i = 0; i < count; ++i) bounds_[static_cast<std::size_t>(i)] = std::tan(angleLo + i * step);
    bounds_.back() = std::tan(angleHi);
    estimateOrigin_ = angleLo;
    estimateScale_ = 1.0 / step;
}

}  // namespace raycache
