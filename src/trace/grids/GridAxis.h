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

#include "core/DoubleLanes.h"

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
    // cellOf for kDoubleLanes values at once, lane by lane the same cell.
    // A uniform axis computes the boundaries next to the estimate as
    // setUniform does (the same bits); the estimate is within one cell of
    // the value's, so one step settles it. An angular axis reads them, and
    // steps while any lane still needs a step (rarely more than one).
    [[gnu::always_inline]] void cellsOf(const DoubleLanes& value, IntLanes& cells) const {
        DoubleLanes estimate = value;
        if (angular_) approximateAtan(estimate);
        estimate = (estimate - estimateOrigin_) * estimateScale_;
        // As cellOf: a NaN estimate gives cell 0.
        estimate = estimate > 0.0 ? estimate : DoubleLanes{};
        estimate = estimate < lastCell_ ? estimate : lastCell_ + DoubleLanes{};
        cells = __builtin_convertvector(estimate, IntLanes);
        const IntLanes last = count_ - 1 + IntLanes{};
        if (!angular_) {
            const DoubleLanes index = __builtin_convertvector(cells, DoubleLanes);
            const DoubleLanes here = estimateOrigin_ + index * step_;
            DoubleLanes next = estimateOrigin_ + (index + 1.0) * step_;
            next = index < lastCell_ ? next : bounds_.back() + DoubleLanes{};
            const IntLanes up = (cells < last) & __builtin_convertvector(value >= next, IntLanes);
            const IntLanes down = (cells > 0) & __builtin_convertvector(value < here, IntLanes);
            cells = cells - up + down;  // masks are -1 where they hold
            return;
        }
        const double* bounds = bounds_.data();
        for (;;) {
            // cells <= count_ - 1, so cells + 1 indexes bounds_ (count_ + 1 entries).
            const DoubleLanes next{bounds[cells[0] + 1], bounds[cells[1] + 1], bounds[cells[2] + 1],
                                   bounds[cells[3] + 1]};
            const IntLanes up = (cells < last) & __builtin_convertvector(value >= next, IntLanes);
            if (!anyLane(up)) break;
            cells -= up;
        }
        for (;;) {
            const DoubleLanes here{bounds[cells[0]], bounds[cells[1]], bounds[cells[2]], bounds[cells[3]]};
            const IntLanes down = (cells > 0) & __builtin_convertvector(value < here, IntLanes);
            if (!anyLane(down)) break;
            cells += down;
        }
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
    // Within 0.005 rad of atan: only the estimate depends on it, never the
    // cell. x / (1 + k x²) inside [-1, 1], ±π/2 - x / (x² + k) outside.
    static constexpr double kHalfPi = 1.5707963267948966, kAtanEstimate = 0.28086;
    static double approximateAtan(double x) {
        if (x >= -1.0 && x <= 1.0) return x / (1.0 + kAtanEstimate * x * x);
        return (x > 0.0 ? kHalfPi : -kHalfPi) - x / (x * x + kAtanEstimate);
    }
    // The same for kDoubleLanes values, in place.
    [[gnu::always_inline]] static void approximateAtan(DoubleLanes& x) {
        const DoubleLanes inner = x / (1.0 + kAtanEstimate * x * x);
        const DoubleLanes outer =
            (x > 0.0 ? kHalfPi + DoubleLanes{} : -kHalfPi + DoubleLanes{}) - x / (x * x + kAtanEstimate);
        x = ((x >= -1.0) & (x <= 1.0)) ? inner : outer;
    }
    [[gnu::always_inline]] static bool anyLane(const IntLanes& mask) {
        return (mask[0] | mask[1] | mask[2] | mask[3]) != 0;
    }

    std::vector<double> bounds_{0.0, 1.0};
    int count_ = 1;
    double lastCell_ = 0.0;  // count_ - 1, converted once
    bool angular_ = false;
    double estimateOrigin_ = 0.0, estimateScale_ = 1.0;
    double step_ = 1.0;  // a uniform axis's boundaries: estimateOrigin_ + i step_, the last one exact
};

}  // namespace raycache
