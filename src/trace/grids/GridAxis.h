#pragma once
// The cells along one axis of a frustum grid: `count` cells between the
// boundaries b[0] <= ... <= b[count], in the coordinate the grid measures
// rays and primitives in (planar x/z or x across, depth z along).
//
// A value's cell is the last one whose lower boundary it reaches, clamped
// to [0, count - 1]. That is a monotonic function of the value, which is
// all the binning and the traversal need to agree: a hit lies between its
// primitive's bounds, so its cell lies between their cells.
//
// Uniform axes space the boundaries evenly. Angular axes space them evenly
// in atan of the value: the document's azimuth and elevation of a light's
// space, with the boundaries stored as tangents, so a cell is found without
// an atan per ray: a cheap estimate of the cell, then the boundaries decide.
#include <vector>

namespace raycache {

class GridAxis {
public:
    // Boundaries lo + i (hi - lo) / count.
    void setUniform(double lo, double hi, int count);
    // Boundaries tan(angleLo + i (angleHi - angleLo) / count); both angles in (-pi/2, pi/2).
    void setAngular(double angleLo, double angleHi, int count);

    int count() const { return count_; }
    double lower() const { return bounds_.front(); }
    double upper() const { return bounds_.back(); }
    double boundary(int i) const { return bounds_[static_cast<std::size_t>(i)]; }

    [[gnu::always_inline]] int cellOf(double value) const {
        const double estimate = ((angular_ ? approximateAtan(value) : value) - estimateOrigin_) * estimateScale_;
        // Written so that a NaN estimate gives cell 0, not an undefined conversion.
        int i = estimate > 0.0 ? (estimate < lastCell_ ? static_cast<int>(estimate) : count_ - 1) : 0;
        const double* bounds = bounds_.data();
        while (i + 1 < count_ && value >= bounds[i + 1]) ++i;
        while (i > 0 && value < bounds[i]) --i;
        return i;
    }
    // The cell of numerator / denominator (denominator > 0), found from
    // `hint` (a neighbour's cell: camera rays come row by row, mostly in the
    // column of the ray before) by comparing products with the boundaries,
    // with no division. The product rounds differently from the quotient
    // only at a boundary, within an ulp: far inside the margins every
    // primitive is binned with, so either neighbour holds what the ray
    // meets. Without a hint (hint < 0) the quotient's cell is the first guess.
    [[gnu::always_inline]] int cellOfRatio(double numerator, double denominator, int hint) const {
        int i = hint < 0 ? cellOf(numerator / denominator) : (hint < count_ ? hint : count_ - 1);
        const double* bounds = bounds_.data();
        while (i + 1 < count_ && numerator >= bounds[i + 1] * denominator) ++i;
        while (i > 0 && numerator < bounds[i] * denominator) --i;
        return i;
    }

private:
    // Within 0.005 rad of atan: only the estimate depends on it, never the cell.
    static double approximateAtan(double x) {
        constexpr double kHalfPi = 1.5707963267948966;
        if (x >= -1.0 && x <= 1.0) return x / (1.0 + 0.28086 * x * x);
        return (x > 0.0 ? kHalfPi : -kHalfPi) - x / (x * x + 0.28086);
    }

    std::vector<double> bounds_{0.0, 1.0};
    int count_ = 1;
    double lastCell_ = 0.0;  // count_ - 1, converted once
    bool angular_ = false;
    double estimateOrigin_ = 0.0, estimateScale_ = 1.0;
};

}  // namespace raycache
