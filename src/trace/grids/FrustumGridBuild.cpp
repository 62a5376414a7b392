// FrustumGrid: the grid built (primitives binned into cells, the cells'
// lists sorted), and what its occupied cells bound.
#include "trace/grids/FrustumGrid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/DoubleLanes.h"
#include "core/Errors.h"
#include "core/FloatLanes.h"
#include "core/LaneLevels.h"

namespace raycache {

namespace {

// Primitives per task when binning: small enough to balance, large enough
// that the task overhead vanishes.
constexpr std::uint32_t kBinBlock = 4096;
static_assert(kBinBlock % kDoubleLanes == 0);
// FrustumGridSpec::refineAboveSlices: how much finer columns may become, per axis.
constexpr double kMaxColumnRefinement = 4.0;

// A corner of a polygon being clipped. Unlike Point3d it is not
// zero-initialised: a Polygon is made twice per primitive per grid, and
// clearing its nine unused corners took a fifth of the binning.
struct PolygonPoint {
    double x, y, z;
};

struct Polygon {
    PolygonPoint points[9];
    int count = 0;
};

// The part of a convex polygon with z >= plane (Sutherland-Hodgman).
Polygon clipBelow(const Polygon& in, double plane) {
    Polygon out;
    for (int i = 0; i < in.count; ++i) {
        const PolygonPoint& a = in.points[i];
        const PolygonPoint& b = in.points[(i + 1) % in.count];
        const bool aIn = a.z >= plane, bIn = b.z >= plane;
        if (aIn) out.points[out.count++] = a;
        if (aIn != bIn) {
            const double f = (plane - a.z) / (b.z - a.z);
            out.points[out.count++] = {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), plane};
        }
    }
    return out;
}

bool boxesOverlap(const FrameBox& a, const FrameBox& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y && a.lo.z <= b.hi.z &&
           b.lo.z <= a.hi.z;
}

}  // namespace

// The primitive's corners in frame coordinates: a triangle's three, or the
// eight of a sphere's box (a sphere's box is the same in any frame).
static Polygon cornersOf(const GridFrame& frame, const GridPrimitives& primitives, std::uint32_t primitive,
                         bool& isBox) {
    Polygon polygon;
    if (const Sphere* sphere = primitives.sphere(primitive)) {
        isBox = true;
        const Point3d c = frame.toFrame(sphere->center);
        const double r = sphere->radius;
        for (int k = 0; k < 8; ++k)
            polygon.points[k] = {c.x + ((k & 1) ? r : -r), c.y + ((k & 2) ? r : -r), c.z + ((k & 4) ? r : -r)};
        polygon.count = 8;
        return polygon;
    }
    isBox = false;
    Vec3 p0, p1, p2;
    primitives.triangle(primitive, p0, p1, p2);
    const Point3d corners[3] = {frame.toFrame(p0), frame.toFrame(p1), frame.toFrame(p2)};
    for (int k = 0; k < 3; ++k) polygon.points[k] = {corners[k].x, corners[k].y, corners[k].z};
    polygon.count = 3;
    return polygon;
}

// The depth range (frame z) of a primitive, without its other coordinates:
// the first pass of a build needs nothing else.
static void depthRangeOf(const GridFrame& frame, const GridPrimitives& primitives, std::uint32_t primitive, double& lo,
                         double& hi) {
    const Point3d& f = frame.forward;
    const auto depth = [&](const Vec3& p) {
        return (p.x - frame.apex.x) * f.x + (p.y - frame.apex.y) * f.y + (p.z - frame.apex.z) * f.z;
    };
    if (const Sphere* sphere = primitives.sphere(primitive)) {
        const double z = depth(sphere->center), r = sphere->radius;
        lo = std::min(lo, z - r);
        hi = std::max(hi, z + r);
        return;
    }
    Vec3 p0, p1, p2;
    primitives.triangle(primitive, p0, p1, p2);
    const double z0 = depth(p0), z1 = depth(p1), z2 = depth(p2);
    lo = std::min({lo, z0, z1, z2});
    hi = std::max({hi, z0, z1, z2});
}

FrustumGrid::CellRange FrustumGrid::binPrimitive(std::uint32_t primitive, bool& inNearZone, PlanarBox& box) const {
    const GridFrame& frame = spec_.frame;
    const double m = spec_.margin;
    bool isBox = false;
    Polygon polygon = cornersOf(frame, *primitives_, primitive, isBox);
    FrameBox bounds{{kFrustumInfinity, kFrustumInfinity, kFrustumInfinity}, {-kFrustumInfinity, -kFrustumInfinity, -kFrustumInfinity}};
    for (int i = 0; i < polygon.count; ++i) {
        const PolygonPoint& p = polygon.points[i];
        bounds.lo = {std::min(bounds.lo.x, p.x), std::min(bounds.lo.y, p.y), std::min(bounds.lo.z, p.z)};
        bounds.hi = {std::max(bounds.hi.x, p.x), std::max(bounds.hi.y, p.y), std::max(bounds.hi.z, p.z)};
    }
    inNearZone = false;
    if (frame.perspective() && bounds.lo.z - m < spec_.zNear) {
        const FrameBox padded{{bounds.lo.x - m, bounds.lo.y - m, bounds.lo.z - m},
                              {bounds.hi.x + m, bounds.hi.y + m, bounds.hi.z + m}};
        inNearZone = boxesOverlap(padded, spec_.nearZone);
    }
    const double zA = std::max(bounds.lo.z - m, zLo_), zB = std::min(bounds.hi.z + m, zHi_);
    if (zA > zB) return kNoCells;
    double sLo = kFrustumInfinity, sHi = -kFrustumInfinity, tLo = kFrustumInfinity, tHi = -kFrustumInfinity;
    if (frame.perspective()) {
        // Only the part in front of the first slice projects into the grid.
        if (bounds.lo.z < zLo_) {
            if (isBox) {
                for (int i = 0; i < polygon.count; ++i) polygon.points[i].z = std::max(polygon.points[i].z, zLo_);
            } else {
                polygon = clipBelow(polygon, zLo_);
            }
        }
        for (int i = 0; i < polygon.count; ++i) {
            const PolygonPoint& p = polygon.points[i];
            // One division: x (1/z) is within an ulp or two of x/z, far below the margin.
            const double inverseZ = 1.0 / p.z;
            const double u = p.x * inverseZ, v = p.y * inverseZ;
            // Moving the point by m moves its projection by at most m (1 + |u|) / z.
            const double mu = m * (1.0 + std::fabs(u)) * inverseZ, mv = m * (1.0 + std::fabs(v)) * inverseZ;
            sLo = std::min(sLo, u - mu);
            sHi = std::max(sHi, u + mu);
            tLo = std::min(tLo, v - mv);
            tHi = std::max(tHi, v + mv);
        }
        if (polygon.count == 0) return kNoCells;
    } else {
        sLo = bounds.lo.x - m;
        sHi = bounds.hi.x + m;
        tLo = bounds.lo.y - m;
        tHi = bounds.hi.y + m;
    }
    if (sHi < sAxis_.lower() || sLo > sAxis_.upper() || tHi < tAxis_.lower() || tLo > tAxis_.upper()) return kNoCells;
    return cellRangeOf(sLo, sHi, tLo, tHi, zA, zB, box);
}

namespace {

// A float not below `value` (direction +1) or not above it (-1): moved
// outward by four times the float rounding before the conversion, which
// rounds by at most half a float ulp (2^-24 relative; 1e-30 covers the
// denormals). Cheaper than std::nextafter, a library call per bound.
float roundedOutward(double value, double direction) {
    return static_cast<float>(value + direction * (std::fabs(value) * 0x1p-22 + 1e-30));
}

}  // namespace

inline FrustumGrid::CellRange FrustumGrid::cellRangeOf(double sLo, double sHi, double tLo, double tHi, double zA, double zB,
                                                PlanarBox& box) const {
    // Within the rectangle (rays outside it are refused), so the floats are finite.
    sLo = std::max(sLo, sAxis_.lower());
    sHi = std::min(sHi, sAxis_.upper());
    tLo = std::max(tLo, tAxis_.lower());
    tHi = std::min(tHi, tAxis_.upper());
    box = {roundedOutward(sLo, -1.0), roundedOutward(sHi, 1.0), roundedOutward(tLo, -1.0), roundedOutward(tHi, 1.0)};
    return {sAxis_.cellOf(sLo), sAxis_.cellOf(sHi),    tAxis_.cellOf(tLo),
            tAxis_.cellOf(tHi), depthAxis_.cellOf(zA), depthAxis_.cellOf(zB)};
}

#define RAYCACHE_LANE_KERNELS "trace/grids/FrustumGridBuildKernels.inc"
#define RAYCACHE_LANE_LEVELS_UP_TO_AVX2
#include "core/LaneLevelsInclude.h"

void FrustumGrid::binPrimitives(std::uint32_t first, std::uint32_t count, PrimitiveFilter filter, std::uint64_t& pairs,
                                std::uint32_t& binned) {
    RAYCACHE_LANE_DISPATCH_UP_TO_AVX2(FrustumGridBuildKernels::binPrimitives, *this, first, count, filter, pairs, binned);
}

void FrustumGrid::build(const FrustumGridSpec& spec, const GridPrimitives& primitives, const Parallel& parallel,
                        PrimitiveFilter filter) {
    spec_ = spec;
    primitives_ = &primitives;
    // A camera packet's key holds a column's indices in kColumnBits each.
    if (spec_.nx < 1 || spec_.ny < 1 || spec_.nx > static_cast<int>(kColumnMask) ||
        spec_.ny > static_cast<int>(kColumnMask))
        throw RuntimeError("a frustum grid of " + std::to_string(spec_.nx) + " x " + std::to_string(spec_.ny) +
                           " columns is out of range");
    stats_ = {};
    const std::uint32_t count = primitives.count();
    const int blocks = static_cast<int>((count + kBinBlock - 1) / kBinBlock);
    auto blockRange = [&](int b) {
        const std::uint32_t begin = static_cast<std::uint32_t>(b) * kBinBlock;
        return std::pair{begin, std::min(count, begin + kBinBlock)};
    };

    // 1. The depth range of all geometry in this frame (of the candidates):
    //    beyond it a ray meets nothing.
    struct BlockDepth {
        double lo = kFrustumInfinity, hi = -kFrustumInfinity;
        std::uint32_t candidates = 0;
    };
    std::vector<BlockDepth> blockDepth(static_cast<std::size_t>(blocks));
    parallel.forEachIndex(blocks, [&](int b, int) {
        auto [begin, end] = blockRange(b);
        BlockDepth& depth = blockDepth[static_cast<std::size_t>(b)];
        for (std::uint32_t p = begin; p < end; ++p)
            if (filter.admits(p)) {
                depthRangeOf(spec_.frame, primitives, p, depth.lo, depth.hi);
                ++depth.candidates;
            }
    });
    geometryZLo_ = kFrustumInfinity;
    geometryZHi_ = -kFrustumInfinity;
    std::uint32_t candidates = 0;
    for (const BlockDepth& depth : blockDepth) {
        geometryZLo_ = std::min(geometryZLo_, depth.lo - spec_.margin);
        geometryZHi_ = std::max(geometryZHi_, depth.hi + spec_.margin);
        candidates += depth.candidates;
    }
    // A crowded grid gets finer columns rather than more slices (light
    // grids: their rays cross every slice up to the light).
    if (spec_.refineAboveSlices > 0) {
        const double slicesWanted =
            spec_.cellsPerPrimitive * candidates / (static_cast<double>(spec_.nx) * spec_.ny);
        if (slicesWanted > spec_.refineAboveSlices) {
            const double refinement = std::min(kMaxColumnRefinement, std::sqrt(slicesWanted / spec_.refineAboveSlices));
            const auto refine = [&](int columns) {
                return static_cast<int>(std::min(std::ceil(columns * refinement), static_cast<double>(kColumnMask)));
            };
            spec_.nx = refine(spec_.nx);
            spec_.ny = refine(spec_.ny);
        }
    }
    zLo_ = spec_.frame.perspective() ? std::max(spec_.zNear, geometryZLo_) : geometryZLo_;
    zHi_ = std::min(geometryZHi_, spec_.zFarLimit);
    if (spec_.frame.mapping == GridMapping::Angular) {
        sAxis_.setAngular(spec_.s0, spec_.s1, spec_.nx);
        tAxis_.setAngular(spec_.t0, spec_.t1, spec_.ny);
    } else {
        sAxis_.setUniform(spec_.s0, spec_.s1, spec_.nx);
        tAxis_.setUniform(spec_.t0, spec_.t1, spec_.ny);
    }
    const double columns = static_cast<double>(spec_.nx) * spec_.ny;
    nz_ = std::clamp(static_cast<int>(spec_.cellsPerPrimitive * candidates / columns), 1, spec_.maxSlices);
    // Slices of depth 1 when there is no geometry: nothing is binned, and no ray walks them.
    depthAxis_.setUniform(zLo_, zHi_ > zLo_ ? zHi_ : zLo_ + nz_, nz_);
    apex_ = Vec3{static_cast<float>(spec_.frame.apex.x), static_cast<float>(spec_.frame.apex.y),
                 static_cast<float>(spec_.frame.apex.z)};
    {
        const FrameBox& box = spec_.nearZone;
        const double zn = spec_.zNear;
        apexRays_ = spec_.frame.mapping == GridMapping::Perspective && zn > 0.0 &&
                    apex_.x == spec_.frame.apex.x && apex_.y == spec_.frame.apex.y && apex_.z == spec_.frame.apex.z &&
                    box.lo.x <= std::min(0.0, spec_.s0 * zn) && box.hi.x >= std::max(0.0, spec_.s1 * zn) &&
                    box.lo.y <= std::min(0.0, spec_.t0 * zn) && box.hi.y >= std::max(0.0, spec_.t1 * zn) &&
                    box.lo.z <= 0.0 && box.hi.z >= zn;
    }
    stats_.nx = spec_.nx;
    stats_.ny = spec_.ny;
    stats_.nz = nz_;
    const std::uint64_t cells = static_cast<std::uint64_t>(spec_.nx) * spec_.ny * nz_;

    // 2. Every primitive's box of cells.
    ranges_.resize(count);
    boxes_.resize(count);
    nearFlags_.resize(count);
    // Per block: its pairs and its primitives with cells.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> blockPairs(static_cast<std::size_t>(blocks));
    parallel.forEachIndex(blocks, [&](int b, int) {
        auto [begin, end] = blockRange(b);
        // Counted here, stored once: neighbouring blocks' entries share a cache line.
        std::uint64_t pairsHere = 0;
        std::uint32_t binnedHere = 0;
        // Four primitives at a time (kBinBlock is a multiple of four).
        for (std::uint32_t p = begin; p < end; p += kDoubleLanes)
            binPrimitives(p, std::min<std::uint32_t>(kDoubleLanes, end - p), filter, pairsHere, binnedHere);
        blockPairs[static_cast<std::size_t>(b)] = {pairsHere, binnedHere};
    });
    std::uint64_t pairs = 0;
    for (const auto& [blockPairsHere, binnedHere] : blockPairs) {
        pairs += blockPairsHere;
        stats_.primitivesBinned += binnedHere;
    }
    stats_.pairs = pairs;
    nearZone_.clear();
    for (auto at = nearFlags_.begin(); (at = std::find(at, nearFlags_.end(), 1)) != nearFlags_.end(); ++at)
        nearZone_.push_back(static_cast<std::uint32_t>(at - nearFlags_.begin()));
    stats_.nearZone = nearZone_.size();

    // 3. The (cell, primitive) pairs sorted by cell, each cell's primitives
    //    in primitive order (CellLists: a counting sort on the cell index).
    cellLists_.build(count, cells, pairs, parallel, [&](std::uint32_t p, auto&& visit) {
        const CellRange& r = ranges_[p];
        for (int j = r.j0; j <= r.j1; ++j)
            for (int i = r.i0; i <= r.i1; ++i)
                for (int k = r.k0; k <= r.k1; ++k) visit(flatCell(k, j, i));
    });
}

std::vector<Vec3> FrustumGrid::occupiedColumnCorners() const {
    std::vector<Vec3> corners;
    if (zLo_ > zHi_ || !spec_.frame.perspective()) return corners;
    // Columns that share a corner share its line from the apex: per lattice
    // corner, the nearest and farthest occupied depth of the (up to four)
    // columns around it. The points between lie on that line, so the two
    // ends have the same hull as every column's own eight corners, with a
    // quarter of the points.
    const std::size_t across = static_cast<std::size_t>(spec_.nx) + 1;
    const std::size_t latticeCorners = across * (static_cast<std::size_t>(spec_.ny) + 1);
    std::vector<double> nearest(latticeCorners, kFrustumInfinity), farthest(latticeCorners, -kFrustumInfinity);
    for (int j = 0; j < spec_.ny; ++j)
        for (int i = 0; i < spec_.nx; ++i) {
            int first = -1, last = -1;
            for (int k = 0; k < nz_; ++k) {
                const std::size_t cell = flatCell(k, j, i);
                if (cellLists_.cellStart()[cell + 1] > cellLists_.cellStart()[cell]) {
                    if (first < 0) first = k;
                    last = k;
                }
            }
            if (first < 0) continue;
            const double zFirst = sliceLower(first), zLast = sliceLower(last + 1);
            for (int corner = 0; corner < 4; ++corner) {
                const std::size_t at = (static_cast<std::size_t>(j) + static_cast<std::size_t>(corner >> 1)) * across +
                                       static_cast<std::size_t>(i) + static_cast<std::size_t>(corner & 1);
                nearest[at] = std::min(nearest[at], zFirst);
                farthest[at] = std::max(farthest[at], zLast);
            }
        }
    const GridFrame& f = spec_.frame;
    for (int j = 0; j <= spec_.ny; ++j)
        for (int i = 0; i <= spec_.nx; ++i) {
            const std::size_t at = static_cast<std::size_t>(j) * across + static_cast<std::size_t>(i);
            if (nearest[at] > farthest[at]) continue;
            // The axes' boundaries are planar values (x/z): a corner's direction at depth 1.
            const double uu = sAxis_.boundary(i), vv = tAxis_.boundary(j);
            for (const double z : {nearest[at], farthest[at]})
                corners.push_back(
                    Vec3{static_cast<float>(f.apex.x + z * (uu * f.right.x + vv * f.up.x + f.forward.x)),
                         static_cast<float>(f.apex.y + z * (uu * f.right.y + vv * f.up.y + f.forward.y)),
                         static_cast<float>(f.apex.z + z * (uu * f.right.z + vv * f.up.z + f.forward.z))});
        }
    return corners;
}

}  // namespace raycache
