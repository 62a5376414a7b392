#include "trace/grids/FrustumGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/DoubleLanes.h"
#include "core/Errors.h"

namespace raycache {

namespace {

constexpr double kFrustumInfinity = std::numeric_limits<double>::infinity();
// A camera packet's key: its column (i, j), whether it crosses the near
// zone, and its shear axes (kz, then kx; ky follows), in one integer.
constexpr int kColumnBits = 24;
constexpr std::uint64_t kColumnMask = (std::uint64_t{1} << kColumnBits) - 1;
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

using FloatLanes = float __attribute__((vector_size(16)));

// The same for kDoubleLanes values.
[[gnu::always_inline]] inline void roundedOutward(const DoubleLanes& value, double direction, FloatLanes& rounded) {
    const DoubleLanes magnitude = value < 0.0 ? -value : value;
    rounded = __builtin_convertvector(value + direction * (magnitude * 0x1p-22 + 1e-30), FloatLanes);
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

// Cloned for AVX2 and baseline x86-64, as generalTraversals: the triangles'
// corners, bounds and projections are one vector per quantity for four
// triangles, the same operations as binPrimitive's lane by lane. A lane that
// is a sphere or must be clipped takes binPrimitive itself.
RAYCACHE_LANE_CLONES
void FrustumGrid::binPrimitives(std::uint32_t first, std::uint32_t count, PrimitiveFilter filter, std::uint64_t& pairs,
                                std::uint32_t& binned) {
    const GridFrame& frame = spec_.frame;
    const double m = spec_.margin;
    // The corners in frame coordinates; lanes past `count` repeat the first
    // primitive, their results unused.
    DoubleLanes x[3], y[3], z[3];
    for (std::uint32_t l = 0; l < static_cast<std::uint32_t>(kDoubleLanes); ++l) {
        const GridPrimitives::TriangleCoordinates& c = primitives_->triangleCoordinates(first + (l < count ? l : 0));
        for (int k = 0; k < 3; ++k) {
            x[k][l] = c[static_cast<std::size_t>(3 * k)];
            y[k][l] = c[static_cast<std::size_t>(3 * k + 1)];
            z[k][l] = c[static_cast<std::size_t>(3 * k + 2)];
        }
    }
    DoubleLanes loX = kFrustumInfinity + DoubleLanes{}, loY = loX, loZ = loX, hiX = -loX, hiY = hiX, hiZ = hiX;
    for (int k = 0; k < 3; ++k) {
        frame.toFrame(x[k], y[k], z[k]);
        keepMin(loX, x[k]);
        keepMin(loY, y[k]);
        keepMin(loZ, z[k]);
        keepMax(hiX, x[k]);
        keepMax(hiY, y[k]);
        keepMax(hiZ, z[k]);
    }
    const FrameBox& zone = spec_.nearZone;
    const LaneMask nearZone = frame.perspective()
                                  ? (loZ - m < spec_.zNear) & (loX - m <= zone.hi.x) & (zone.lo.x <= hiX + m) &
                                        (loY - m <= zone.hi.y) & (zone.lo.y <= hiY + m) & (loZ - m <= zone.hi.z) &
                                        (zone.lo.z <= hiZ + m)
                                  : LaneMask{};
    DoubleLanes zA = loZ - m, zB = hiZ + m;
    keepMax(zA, zLo_ + DoubleLanes{});
    keepMin(zB, zHi_ + DoubleLanes{});
    const LaneMask clipped = frame.perspective() ? loZ < zLo_ : LaneMask{};
    DoubleLanes sLo, sHi, tLo, tHi;
    if (frame.perspective()) {
        sLo = tLo = kFrustumInfinity + DoubleLanes{};
        sHi = tHi = -sLo;
        for (int k = 0; k < 3; ++k) {
            // One division: x (1/z) is within an ulp or two of x/z, far below the margin.
            const DoubleLanes inverseZ = 1.0 / z[k];
            const DoubleLanes u = x[k] * inverseZ, v = y[k] * inverseZ;
            // Moving the point by m moves its projection by at most m (1 + |u|) / z.
            const DoubleLanes mu = m * (1.0 + (u < 0.0 ? -u : u)) * inverseZ;
            const DoubleLanes mv = m * (1.0 + (v < 0.0 ? -v : v)) * inverseZ;
            keepMin(sLo, u - mu);
            keepMax(sHi, u + mu);
            keepMin(tLo, v - mv);
            keepMax(tHi, v + mv);
        }
    } else {
        sLo = loX - m;
        sHi = hiX + m;
        tLo = loY - m;
        tHi = hiY + m;
    }
    const LaneMask outside = (zA > zB) | (sHi < sAxis_.lower()) | (sLo > sAxis_.upper()) | (tHi < tAxis_.lower()) |
                             (tLo > tAxis_.upper());
    // How each lane is binned: not at all (filtered out, or outside the
    // grid), by binPrimitive (a sphere, or a triangle to clip), or from the
    // vectors below. A light's face grid admits few primitives: when no lane
    // takes its cells from the vectors, they are not computed.
    enum class LaneBinning : unsigned char { FilteredOut, Scalar, Outside, FromVectors };
    LaneBinning binning[kDoubleLanes] = {};
    bool anyFromVectors = false;
    for (std::uint32_t l = 0; l < count; ++l) {
        const std::uint32_t p = first + l;
        if (!filter.admits(p)) binning[l] = LaneBinning::FilteredOut;
        else if (primitives_->sphere(p) || (clipped[l] != 0 && !(zA[l] > zB[l]))) binning[l] = LaneBinning::Scalar;
        else if (outside[l] != 0) binning[l] = LaneBinning::Outside;
        else binning[l] = LaneBinning::FromVectors;
        anyFromVectors |= binning[l] == LaneBinning::FromVectors;
    }
    // cellRangeOf for the four lanes: its clamps, rounding and cells, lane by lane the same.
    FloatLanes boxSLo{}, boxSHi{}, boxTLo{}, boxTHi{};
    IntLanes i0{}, i1{}, j0{}, j1{}, k0{}, k1{};
    if (anyFromVectors) {
        keepMax(sLo, sAxis_.lower() + DoubleLanes{});
        keepMin(sHi, sAxis_.upper() + DoubleLanes{});
        keepMax(tLo, tAxis_.lower() + DoubleLanes{});
        keepMin(tHi, tAxis_.upper() + DoubleLanes{});
        roundedOutward(sLo, -1.0, boxSLo);
        roundedOutward(sHi, 1.0, boxSHi);
        roundedOutward(tLo, -1.0, boxTLo);
        roundedOutward(tHi, 1.0, boxTHi);
        sAxis_.cellsOf(sLo, i0);
        sAxis_.cellsOf(sHi, i1);
        tAxis_.cellsOf(tLo, j0);
        tAxis_.cellsOf(tHi, j1);
        depthAxis_.cellsOf(zA, k0);
        depthAxis_.cellsOf(zB, k1);
    }
    for (std::uint32_t l = 0; l < count; ++l) {
        const std::uint32_t p = first + l;
        CellRange& range = ranges_[p];
        bool inNearZone = false;
        switch (binning[l]) {
            case LaneBinning::FilteredOut:
                range = kNoCells;
                break;
            case LaneBinning::Scalar:
                range = binPrimitive(p, inNearZone, boxes_[p]);
                break;
            case LaneBinning::Outside:
                inNearZone = nearZone[l] != 0;
                range = kNoCells;
                break;
            case LaneBinning::FromVectors:
                inNearZone = nearZone[l] != 0;
                range = {i0[l], i1[l], j0[l], j1[l], k0[l], k1[l]};
                boxes_[p] = {boxSLo[l], boxSHi[l], boxTLo[l], boxTHi[l]};
                break;
        }
        nearFlags_[p] = inNearZone ? 1 : 0;
        if (range.i1 >= range.i0) {
            pairs += static_cast<std::uint64_t>(range.i1 - range.i0 + 1) * (range.j1 - range.j0 + 1) *
                     (range.k1 - range.k0 + 1);
            ++binned;
        }
    }
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

bool FrustumGrid::apexColumn(const Ray& ray, Point3d& d, ApexColumn& column) const {
    // The origin is the apex exactly, so it is (0, 0, 0) in the frame.
    if (!(ray.origin.x == apex_.x && ray.origin.y == apex_.y && ray.origin.z == apex_.z)) return false;
    d = spec_.frame.directionToFrame(ray.direction);
    // The segment must start before the first slice and end beyond the
    // last, with slices and no geometry past them (a light grid's end).
    if (!(d.z > 0.0) || zLo_ > zHi_ || zHi_ < geometryZHi_ || !(ray.tNear * d.z <= zLo_) ||
        !(ray.tFar * d.z >= geometryZHi_))
        return false;
    // Inside the rectangle: lower <= x/z <= upper, as products (z > 0).
    if (!(d.x >= sAxis_.lower() * d.z && d.x <= sAxis_.upper() * d.z && d.y >= tAxis_.lower() * d.z &&
          d.y <= tAxis_.upper() * d.z))
        return false;
    // Through the rectangle from the apex, the ray runs inside the frustum's
    // tip up to zNear, which the near zone holds (apexRays_).
    column.nearPart = geometryZLo_ < spec_.zNear && ray.tNear * d.z <= spec_.zNear;
    // On a line through the apex s and t are the same everywhere: one column,
    // found from the column passed in (the ray before's).
    column.i = sAxis_.cellOfRatio(d.x, d.z, column.i);
    column.j = tAxis_.cellOfRatio(d.y, d.z, column.j);
    return true;
}

FrustumGrid::Traversal FrustumGrid::apexWalk(const ApexColumn& column) const {
    Traversal tr;
    tr.origin = {};
    tr.nearPart = column.nearPart;
    tr.gridPart = true;
    tr.i0 = tr.i1 = column.i;
    tr.j0 = tr.j1 = column.j;
    tr.k0 = 0;
    tr.k1 = nz_ - 1;
    tr.ascending = true;
    return tr;
}

FrustumGrid::Traversal FrustumGrid::traversalOf(const Ray& ray) const {
    if (apexRays_) {
        Point3d d;
        ApexColumn column{spec_.nx / 2, spec_.ny / 2, false};
        if (apexColumn(ray, d, column)) {
            Traversal tr = apexWalk(column);
            tr.direction = d;
            return tr;
        }
    }
    return generalTraversal(ray, ColumnHint{});
}

namespace {

// The parameter interval of o + t d with lo <= z <= hi, intersected with
// [ta, tb], for kDoubleLanes rays at once; inverseDz = 1 / dz. Returns the
// lanes where it is not empty (a lane with dz = 0: whether its oz is in
// [lo, hi]). A product where a quotient would do: a traversal clips its rays
// four times, and the ulp the product moves a bound is far inside the margin.
[[gnu::always_inline]] inline void clipDepthLanes(const DoubleLanes& oz, const DoubleLanes& dz,
                                                  const DoubleLanes& inverseDz, double lo, double hi, DoubleLanes& ta,
                                                  DoubleLanes& tb, LaneMask& nonEmpty) {
    const LaneMask flat = dz == 0.0;
    const DoubleLanes t1 = (lo - oz) * inverseDz, t2 = (hi - oz) * inverseDz;
    const LaneMask swapped = t1 > t2;
    DoubleLanes a = ta, b = tb;
    keepMax(a, swapped ? t2 : t1);
    keepMin(b, swapped ? t1 : t2);
    const LaneMask flatInside = (oz >= lo) & (oz <= hi) & (ta <= tb);
    nonEmpty = flat ? flatInside : (a <= b);
    ta = flat ? ta : a;
    tb = flat ? tb : b;
}

// Whether each of kDoubleLanes points lies in the box widened by `margin`.
[[gnu::always_inline]] inline void insideBoxLanes(const DoubleLanes& x, const DoubleLanes& y, const DoubleLanes& z,
                                                  const FrameBox& box, double margin, LaneMask& inside) {
    inside = (x >= box.lo.x - margin) & (x <= box.hi.x + margin) & (y >= box.lo.y - margin) &
             (y <= box.hi.y + margin) & (z >= box.lo.z - margin) & (z <= box.hi.z + margin);
}

}  // namespace

// Cloned for AVX2 and baseline x86-64, as the packets: each quantity of the
// lanes' rays is one DoubleLanes, so the clips and tests below are one AVX2
// instruction for four rays. Only the cells' boundary searches run lane by lane.
RAYCACHE_LANE_CLONES
void FrustumGrid::generalTraversals(std::span<const Ray> rays, Traversal* out, ColumnHint& hint) const {
    const std::size_t n = std::min(rays.size(), static_cast<std::size_t>(kDoubleLanes));
    const GridFrame& frame = spec_.frame;
    // Lanes past n repeat the first ray; their results are not written.
    DoubleLanes ox, oy, oz, dx, dy, dz, tNear, tFar;
    for (std::size_t l = 0; l < static_cast<std::size_t>(kDoubleLanes); ++l) {
        const Ray& ray = rays[l < n ? l : 0];
        ox[l] = ray.origin.x;
        oy[l] = ray.origin.y;
        oz[l] = ray.origin.z;
        dx[l] = ray.direction.x;
        dy[l] = ray.direction.y;
        dz[l] = ray.direction.z;
        tNear[l] = ray.tNear;
        tFar[l] = ray.tFar;
    }
    frame.toFrame(ox, oy, oz);
    frame.directionToFrame(dx, dy, dz);
    const DoubleLanes inverseDz = 1.0 / dz;
    // Lanes still to decide; lanes found not covered; lanes crossing the near zone.
    LaneMask open = ~LaneMask{}, refused = LaneMask{}, nearPart = LaneMask{};
    DoubleLanes ta = tNear, tb = tFar;
    // Outside the depth range of all geometry there is nothing to meet.
    LaneMask clipped;
    if (geometryZLo_ > geometryZHi_) {
        open = LaneMask{};
    } else {
        clipDepthLanes(oz, dz, inverseDz, geometryZLo_, geometryZHi_, ta, tb, clipped);
        open &= clipped;
    }
    LaneMask finiteA, finiteB;
    if (frame.perspective() && geometryZLo_ < spec_.zNear) {
        DoubleLanes na = ta, nb = tb;
        clipDepthLanes(oz, dz, inverseDz, -kFrustumInfinity, spec_.zNear, na, nb, clipped);
        const LaneMask crosses = open & clipped;
        LaneMask insideA, insideB;
        markFinite(na, finiteA);
        markFinite(nb, finiteB);
        insideBoxLanes(ox + na * dx, oy + na * dy, oz + na * dz, spec_.nearZone, spec_.margin, insideA);
        insideBoxLanes(ox + nb * dx, oy + nb * dy, oz + nb * dz, spec_.nearZone, spec_.margin, insideB);
        const LaneMask inside = finiteA & finiteB & insideA & insideB;
        refused |= crosses & ~inside;
        nearPart = crosses & inside;
        open &= ~refused;
    }
    if (zLo_ > zHi_) open = LaneMask{};
    DoubleLanes ga = ta, gb = tb;
    clipDepthLanes(oz, dz, inverseDz, zLo_, kFrustumInfinity, ga, gb, clipped);
    open &= clipped;
    // Geometry beyond the last slice (a light grid ends at the farthest shadow-ray origin).
    if (zHi_ < geometryZHi_) {
        DoubleLanes fa = ga, fb = gb;
        clipDepthLanes(oz, dz, inverseDz, zHi_ + spec_.margin, kFrustumInfinity, fa, fb, clipped);
        const LaneMask beyond = open & clipped;
        refused |= beyond;
        open &= ~beyond;
    }
    markFinite(ga, finiteA);
    markFinite(gb, finiteB);
    const LaneMask unbounded = open & ~(finiteA & finiteB);
    refused |= unbounded;
    open &= ~unbounded;
    const DoubleLanes ax = ox + ga * dx, ay = oy + ga * dy, az = oz + ga * dz;
    const DoubleLanes bx = ox + gb * dx, by = oy + gb * dy, bz = oz + gb * dz;
    // Both ends' planar coordinates (x/z, or x) against the rectangle and
    // the columns' boundaries, as products: z > 0 on perspective frames (the
    // segment starts at zLo_ or beyond).
    const DoubleLanes za = frame.perspective() ? az : DoubleLanes{} + 1.0;
    const DoubleLanes zb = frame.perspective() ? bz : DoubleLanes{} + 1.0;
    const LaneMask inRectangle = (ax >= sAxis_.lower() * za) & (ax <= sAxis_.upper() * za) &
                                 (bx >= sAxis_.lower() * zb) & (bx <= sAxis_.upper() * zb) &
                                 (ay >= tAxis_.lower() * za) & (ay <= tAxis_.upper() * za) &
                                 (by >= tAxis_.lower() * zb) & (by <= tAxis_.upper() * zb);
    refused |= open & ~inRectangle;
    open &= inRectangle;
    // The ends' planar coordinates bound the segment's (packets cull with them).
    const DoubleLanes sa = ax / za, sb = bx / zb, ta2 = ay / za, tb2 = by / zb;
    for (std::size_t l = 0; l < n; ++l) {
        Traversal& tr = out[l];
        tr.covered = refused[l] == 0;
        tr.nearPart = nearPart[l] != 0;
        tr.gridPart = open[l] != 0;
        tr.origin = {ox[l], oy[l], oz[l]};
        tr.direction = {dx[l], dy[l], dz[l]};
        tr.ascending = true;
        if (!tr.gridPart) {
            tr.i0 = tr.j0 = tr.k0 = 0;
            tr.i1 = tr.j1 = tr.k1 = -1;
            continue;
        }
        // A camera ray, and a shadow ray in a point light's space, keeps to
        // one column: its far end is found from its near end's cell.
        const int ia = sAxis_.cellOfRatio(ax[l], za[l], hint.i), ib = sAxis_.cellOfRatio(bx[l], zb[l], ia);
        const int ja = tAxis_.cellOfRatio(ay[l], za[l], hint.j), jb = tAxis_.cellOfRatio(by[l], zb[l], ja);
        tr.i0 = std::min(ia, ib);
        tr.i1 = std::max(ia, ib);
        tr.j0 = std::min(ja, jb);
        tr.j1 = std::max(ja, jb);
        tr.k0 = depthAxis_.cellOf(std::min(az[l], bz[l]));
        tr.k1 = depthAxis_.cellOf(std::max(az[l], bz[l]));
        tr.ascending = dz[l] >= 0.0;
        tr.planar = {std::min(sa[l], sb[l]), std::max(sa[l], sb[l]), std::min(ta2[l], tb2[l]), std::max(ta2[l], tb2[l])};
        hint = ColumnHint{tr.i0, tr.j0};
    }
}

bool FrustumGrid::intersect(const Ray& ray, TraceHit& hit) const {
    const Traversal tr = traversalOf(ray);
    if (!tr.covered) return false;
    TraceHit best;
    const WatertightRay watertight(ray);
    if (tr.nearPart)
        for (const std::uint32_t p : nearZone_) primitives_->intersect(p, ray, watertight, best);
    if (tr.gridPart)
        walkCells(
            tr,
            [&](std::uint32_t primitive) {
                primitives_->intersect(primitive, ray, watertight, best);
                return false;
            },
            [&](int k) {
                return best.hit() && hitEndsWalk(tr, tr.origin.z + static_cast<double>(best.t) * tr.direction.z, k);
            });
    hit = best;
    return true;
}

namespace {

constexpr std::size_t kLanes = 16;

}  // namespace

std::uint64_t FrustumGrid::cameraKey(const ApexColumn& column, const Vec3& direction) {
    int kx = 0, ky = 0, kz = 0;
    WatertightRay::shearAxes(direction, kx, ky, kz);
    return static_cast<std::uint64_t>(column.i) | static_cast<std::uint64_t>(column.j) << kColumnBits |
           static_cast<std::uint64_t>(kz) << (2 * kColumnBits) |
           static_cast<std::uint64_t>(kx) << (2 * kColumnBits + 2) |
           static_cast<std::uint64_t>(column.nearPart ? 1 : 0) << (2 * kColumnBits + 4);
}

FrustumGrid::ApexColumn FrustumGrid::unpackCameraKey(std::uint64_t key) {
    return {static_cast<int>(key & kColumnMask), static_cast<int>((key >> kColumnBits) & kColumnMask),
            ((key >> (2 * kColumnBits + 4)) & 1) != 0};
}

namespace {

// Component k of v by one indexed load (Vec3's operator[] is two branches
// on an index known only at run time, as a packet's shear axes are).
[[gnu::always_inline]] inline float component(const Vec3& v, int k) {
    const float c[3] = {v.x, v.y, v.z};
    return c[k];
}

// A packet lane's shear (WatertightRay's, in its operations, along the
// packet's axes kx, ky, kz) and segment. A padding lane (one past the
// packet's rays, repeating its first) gets an empty segment: it accepts no
// triangle, so never calls for settling.
[[gnu::always_inline]] inline void setLane(const Ray& ray, bool padding, int kx, int ky, int kz, float& sx, float& sy,
                                           float& sz, float& tNear, float& tFar) {
    const float dx = component(ray.direction, kx), dy = component(ray.direction, ky), dz = component(ray.direction, kz);
    sx = dx / dz;
    sy = dy / dz;
    sz = 1.0f / dz;
    tNear = padding ? std::numeric_limits<float>::infinity() : ray.tNear;
    tFar = ray.tFar;
}

// What decides whether two rays can share a packet.
struct PacketKey {
    float ox, oy, oz;
    int kz, kx, ky;
    int i0, i1, j0, j1, k0, k1;
    bool ascending;
    bool nearPart;
    bool operator==(const PacketKey&) const = default;
};

// Gathers rays with equal keys into packets of at most kLanes, in batch
// order within a packet, and hands each full packet, and at flush() every
// partial one, to `packet` as the span of its ray indices. A key is matched
// against the few packets open at the time only: rays that belong together
// come close together in a batch (a tile's camera rays row by row across a
// few columns; a tile's shadow rays, whose origins lie close together in
// the light's space too). An equal key met later
// opens another packet: a packet less full, never another answer, since
// every lane's answer is its own.
template <typename Key>
class PacketGatherer {
public:
    template <typename Packet>
    void add(const Key& key, std::uint32_t ray, Packet&& packet) {
        std::size_t slot = last_;
        if (slot >= used_ || !(open_[slot].key == key)) {
            slot = 0;
            while (slot < used_ && !(open_[slot].key == key)) ++slot;
            if (slot == used_) {
                if (used_ < kOpen) {
                    ++used_;
                } else {
                    // Every slot taken: the slots are handed on and reused in turn.
                    slot = evict_;
                    evict_ = (evict_ + 1) % kOpen;
                    emit(open_[slot], packet);
                }
                open_[slot].key = key;
            }
        }
        last_ = slot;
        Open& open = open_[slot];
        open.lanes[open.count++] = ray;
        if (open.count == kLanes) emit(open, packet);
    }
    template <typename Packet>
    void flush(Packet&& packet) {
        for (std::size_t slot = 0; slot < used_; ++slot) emit(open_[slot], packet);
        used_ = last_ = evict_ = 0;
    }

private:
    static constexpr std::size_t kOpen = 8;
    struct Open {
        Key key{};
        std::size_t count = 0;
        std::uint32_t lanes[kLanes];
    };
    template <typename Packet>
    static void emit(Open& open, Packet& packet) {
        if (open.count > 0) packet(std::span<const std::uint32_t>(open.lanes, open.count), open.key);
        open.count = 0;
    }
    std::array<Open, kOpen> open_{};
    std::size_t used_ = 0, last_ = 0, evict_ = 0;
};

}  // namespace

void FrustumGrid::intersectBatch(std::span<const Ray> rays, std::span<TraceHit> hits,
                                 std::span<unsigned char> refused) const {
    thread_local std::vector<Traversal> traversals;
    PacketGatherer<PacketKey> gatherer;
    const auto trace = [&](std::span<const std::uint32_t> packet, const PacketKey&) {
        PlanarRange planar;
        for (const std::uint32_t ray : packet) planar.add(traversals[ray].planar);
        intersectPacket(rays, packet, traversals[packet[0]], &planar, hits);
    };
    // Camera rays (from the apex through every slice, apexColumn) are keyed
    // by their column and shear axes alone, packed in one integer, and need
    // no Traversal of their own: their packet's walk follows from the key.
    PacketGatherer<std::uint64_t> cameraGatherer;
    const auto traceCamera = [&](std::span<const std::uint32_t> packet, std::uint64_t key) {
        intersectPacket(rays, packet, apexWalk(unpackCameraKey(key)), nullptr, hits);
    };
    traversals.resize(rays.size());
    // Each camera ray's column is looked for from the one before's.
    ApexColumn column{spec_.nx / 2, spec_.ny / 2, false};
    for (std::size_t i = 0; i < rays.size(); ++i) {
        refused[i] = 0;
        if (apexRays_) {
            Point3d direction;
            if (apexColumn(rays[i], direction, column)) {
                cameraGatherer.add(cameraKey(column, rays[i].direction), static_cast<std::uint32_t>(i), traceCamera);
                continue;
            }
        }
        // Written in place: copying a returned record from the stack stalled
        // on store forwarding (a third of occludedBatch's own time on `orbit`).
        ColumnHint hint;
        generalTraversals(rays.subspan(i, 1), &traversals[i], hint);
        const Traversal& tr = traversals[i];
        if (!tr.covered) {
            refused[i] = 1;
            continue;
        }
        if (!tr.gridPart) {
            intersect(rays[i], hits[i]);
            continue;
        }
        // Camera rays share the apex, so those that also cross the near zone
        // (geometry behind or beside the eye: a floor, a room) pack as well.
        int kx = 0, ky = 0, kz = 0;
        WatertightRay::shearAxes(rays[i].direction, kx, ky, kz);
        gatherer.add(PacketKey{rays[i].origin.x, rays[i].origin.y, rays[i].origin.z, kz, kx, ky, tr.i0, tr.i1, tr.j0,
                               tr.j1, tr.k0, tr.k1, tr.ascending, tr.nearPart},
                     static_cast<std::uint32_t>(i), trace);
    }
    gatherer.flush(trace);
    cameraGatherer.flush(traceCamera);
}

// Compiled twice, for AVX2 (8-wide lane loops) and for baseline x86-64
// (4-wide), chosen at load time by the CPU. Both clones give the same bits:
// the lane loops are IEEE additions, multiplications and comparisons, and
// -ffp-contract=off (cmake/Warnings.cmake) keeps them from becoming FMAs.
// An AVX-512 clone measured no faster (docs/performance.md). walkCells is
// always inlined so the lane loops are compiled inside each clone.
RAYCACHE_LANE_CLONES
void FrustumGrid::intersectPacket(std::span<const Ray> rays, std::span<const std::uint32_t> lanes, const Traversal& tr,
                                  const PlanarRange* lanesPlanar, std::span<TraceHit> hits) const {
    const std::size_t n = lanes.size();
    alignas(64) float sx[kLanes], sy[kLanes], sz[kLanes], tNear[kLanes], tFar[kLanes];
    alignas(64) float edgeV[kLanes], edgeW[kLanes], numerator[kLanes], determinant[kLanes];
    alignas(64) float rayDirectionX[kLanes], rayDirectionY[kLanes], rayDirectionZ[kLanes];
    alignas(64) double directionZ[kLanes];
    alignas(64) int accepted[kLanes], zeroEdge[kLanes];
    TraceHit best[kLanes];
    // Lanes with no hit yet: while any is left, no slice can end the walk.
    std::size_t withoutHit = n;
    const Ray& first = rays[lanes[0]];
    // Every lane has the packet's shear axes (the packet key holds them).
    int kx = 0, ky = 0, kz = 0;
    WatertightRay::shearAxes(first.direction, kx, ky, kz);
    const float originX = component(first.origin, kx), originY = component(first.origin, ky),
                originZ = component(first.origin, kz);
    for (std::size_t l = 0; l < kLanes; ++l) {
        // Lanes past n repeat the first ray; their answers are dropped.
        const Ray& ray = rays[lanes[l < n ? l : 0]];
        setLane(ray, l >= n, kx, ky, kz, sx[l], sy[l], sz[l], tNear[l], tFar[l]);
        rayDirectionX[l] = ray.direction.x;
        rayDirectionY[l] = ray.direction.y;
        rayDirectionZ[l] = ray.direction.z;
    }
    // The lanes' directions in frame coordinates, four lanes a vector; for rays from the apex their planar coordinates
    // too, the same all along them. Padding lanes repeat lane 0.
    static_assert(kLanes % kDoubleLanes == 0);
    const GridFrame& frame = spec_.frame;
    DoubleLanes sLo = kFrustumInfinity + DoubleLanes{}, sHi = -sLo, tLo = sLo, tHi = sHi;
    for (std::size_t l = 0; l < kLanes; l += kDoubleLanes) {
        DoubleLanes x, y, z;
        for (int k = 0; k < kDoubleLanes; ++k) {
            x[k] = rayDirectionX[l + static_cast<std::size_t>(k)];
            y[k] = rayDirectionY[l + static_cast<std::size_t>(k)];
            z[k] = rayDirectionZ[l + static_cast<std::size_t>(k)];
        }
        if (lanesPlanar) {
            DoubleLanes frameZ;
            frame.directionZToFrame(x, y, z, frameZ);
            __builtin_memcpy(directionZ + l, &frameZ, sizeof frameZ);
            continue;
        }
        frame.directionToFrame(x, y, z);
        __builtin_memcpy(directionZ + l, &z, sizeof z);
        const DoubleLanes s = x / z, t = y / z;
        keepMin(sLo, s);
        keepMax(sHi, s);
        keepMin(tLo, t);
        keepMax(tHi, t);
    }
    PlanarRange planar;
    if (lanesPlanar)
        planar = *lanesPlanar;
    else
        for (int l = 0; l < kDoubleLanes; ++l) planar.add({sLo[l], sHi[l], tLo[l], tHi[l]});
    // Inlined at both call sites: called out of line, GCC no longer vectorises the lane loop.
    const auto visit = [&](std::uint32_t primitive) __attribute__((always_inline)) {
        if (primitives_->sphere(primitive)) {
            for (std::size_t l = 0; l < n; ++l) {
                const Ray& ray = rays[lanes[l]];
                const bool hadHit = best[l].hit();
                primitives_->intersect(primitive, ray, WatertightRay(ray), best[l]);
                if (best[l].hit()) {
                    tFar[l] = best[l].t;
                    withoutHit -= hadHit ? 0 : 1;
                }
            }
            return false;
        }
        // The packet shares its origin: the corners relative to it are computed once.
        const GridPrimitives::TriangleCoordinates& p = primitives_->triangleCoordinates(primitive);
        const float akx = p[kx] - originX, aky = p[ky] - originY, akz = p[kz] - originZ;
        const float bkx = p[3 + kx] - originX, bky = p[3 + ky] - originY, bkz = p[3 + kz] - originZ;
        const float ckx = p[6 + kx] - originX, cky = p[6 + ky] - originY, ckz = p[6 + kz] - originZ;
        // The watertight test's float path, lane by lane (watertightLane).
        int anyToSettle = 0;
        for (std::size_t l = 0; l < kLanes; ++l) {
            const WatertightLane lane =
                watertightLane(akx, aky, akz, bkx, bky, bkz, ckx, cky, ckz, sx[l], sy[l], sz[l], tNear[l], tFar[l]);
            zeroEdge[l] = static_cast<int>(lane.zeroEdge);
            accepted[l] = static_cast<int>(lane.accepted);
            edgeV[l] = lane.v;
            edgeW[l] = lane.w;
            numerator[l] = lane.t;
            determinant[l] = lane.det;
            anyToSettle |= zeroEdge[l] | accepted[l];
        }
        // Most triangles of a cell miss every lane: nothing to settle.
        if (!anyToSettle) return false;
        const int object = primitives_->objectOf(primitive);
        const int local = primitives_->localIndex(primitive);
        for (std::size_t l = 0; l < n; ++l) {
            if (zeroEdge[l]) {
                // An edge value of exactly zero: the double-precision path, as the scalar test.
                const Ray& ray = rays[lanes[l]];
                const bool hadHit = best[l].hit();
                primitives_->intersect(primitive, ray, WatertightRay(ray), best[l]);
                if (best[l].hit()) {
                    tFar[l] = best[l].t;
                    withoutHit -= hadHit ? 0 : 1;
                }
                continue;
            }
            if (!accepted[l]) continue;
            const float inverseDet = 1.0f / determinant[l];
            const float t = numerator[l] * inverseDet;
            if (GridPrimitives::nearer(t, object, local, best[l])) {
                withoutHit -= best[l].hit() ? 0 : 1;
                best[l] = TraceHit{t, object, local, edgeV[l] * inverseDet, edgeW[l] * inverseDet};
                // Later triangles need only reach the nearest hit so far (a tie at it is decided by ids).
                tFar[l] = t;
            }
        }
        return false;
    };
    // As intersect(): the near zone's primitives first, then the cells.
    if (tr.nearPart)
        for (const std::uint32_t p : nearZone_) visit(p);
    // In the cells, a primitive whose planar box misses every lane's is
    // skipped: most of a cell's triangles miss the whole packet. (A lane's
    // hit nearer than the first slice is in the near zone, tested above.)
    const auto visitCell = [&](std::uint32_t primitive) __attribute__((always_inline)) {
        return missesRange(primitive, planar) ? false : visit(primitive);
    };
    walkCells(tr, visitCell, [&](int k) {
        if (withoutHit > 0) return false;
        for (std::size_t l = 0; l < n; ++l)
            if (!best[l].hit() || !hitEndsWalk(tr, tr.origin.z + static_cast<double>(best[l].t) * directionZ[l], k))
                return false;
        return true;
    });
    for (std::size_t l = 0; l < n; ++l) hits[lanes[l]] = best[l];
}

bool FrustumGrid::occluded(const Ray& ray, bool& blocked) const {
    const Traversal tr = traversalOf(ray);
    if (!tr.covered) return false;
    blocked = false;
    const WatertightRay watertight(ray);
    if (tr.nearPart)
        for (const std::uint32_t p : nearZone_)
            if (primitives_->occludes(p, ray, watertight)) {
                blocked = true;
                return true;
            }
    if (!tr.gridPart) return true;
    walkCells(
        tr, [&](std::uint32_t primitive) { return blocked = primitives_->occludes(primitive, ray, watertight); },
        [](int) { return false; });
    return true;
}

namespace {

// What decides whether two shadow rays can share a packet: not the origin
// (each lane has its own), only the shear axis and the cells' columns.
struct ShadowPacketKey {
    int kz, kx, ky;
    int i0, i1, j0, j1;
    bool ascending;
    bool nearPart;
    bool operator==(const ShadowPacketKey&) const = default;
};

}  // namespace

void FrustumGrid::occludedBatch(std::span<const Ray> rays, std::span<unsigned char> blocked,
                                std::span<unsigned char> refused) const {
    thread_local std::vector<Traversal> traversals;
    PacketGatherer<ShadowPacketKey> gatherer;
    const auto trace = [&](std::span<const std::uint32_t> packet, const ShadowPacketKey&) {
        Traversal walk = traversals[packet[0]];
        for (const std::uint32_t ray : packet) {
            walk.k0 = std::min(walk.k0, traversals[ray].k0);
            walk.k1 = std::max(walk.k1, traversals[ray].k1);
            walk.planar.add(traversals[ray].planar);
        }
        occludedPacket(rays, packet, walk, blocked);
    };
    traversals.resize(rays.size());
    // Each ray's cells are looked for from the last covered ray's: a tile's
    // shadow rays lie close together in the light's space too.
    ColumnHint hint;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        refused[i] = 0;
        blocked[i] = 0;
        // Four rays' traversals at a time, written in place (as in intersectBatch).
        if (i % kDoubleLanes == 0) generalTraversals(rays.subspan(i), &traversals[i], hint);
        const Traversal& tr = traversals[i];
        if (!tr.covered) {
            refused[i] = 1;
            continue;
        }
        if (!tr.gridPart) {
            bool b = false;
            occluded(rays[i], b);
            blocked[i] = b ? 1 : 0;
            continue;
        }
        int kx = 0, ky = 0, kz = 0;
        WatertightRay::shearAxes(rays[i].direction, kx, ky, kz);
        gatherer.add(ShadowPacketKey{kz, kx, ky, tr.i0, tr.i1, tr.j0, tr.j1, tr.ascending, tr.nearPart},
                     static_cast<std::uint32_t>(i), trace);
    }
    gatherer.flush(trace);
}

// Cloned for AVX2 and baseline x86-64, as intersectPacket.
RAYCACHE_LANE_CLONES
void FrustumGrid::occludedPacket(std::span<const Ray> rays, std::span<const std::uint32_t> lanes, const Traversal& walk,
                                 std::span<unsigned char> blocked) const {
    const std::size_t n = lanes.size();
    // Each lane's origin and shear in the packet's common axes (kx, ky, kz).
    alignas(64) float ox[kLanes], oy[kLanes], oz[kLanes], sx[kLanes], sy[kLanes], sz[kLanes];
    alignas(64) float tNear[kLanes], tFar[kLanes];
    alignas(64) int accepted[kLanes], zeroEdge[kLanes];
    bool done[kLanes] = {};
    std::size_t open = n;
    // Every lane has the packet's shear axes (the packet key holds them).
    int kx = 0, ky = 0, kz = 0;
    WatertightRay::shearAxes(rays[lanes[0]].direction, kx, ky, kz);
    for (std::size_t l = 0; l < kLanes; ++l) {
        // Lanes past n repeat the first ray; their answers are dropped.
        const Ray& ray = rays[lanes[l < n ? l : 0]];
        ox[l] = component(ray.origin, kx);
        oy[l] = component(ray.origin, ky);
        oz[l] = component(ray.origin, kz);
        setLane(ray, l >= n, kx, ky, kz, sx[l], sy[l], sz[l], tNear[l], tFar[l]);
    }
    const auto settle = [&](std::size_t l) {
        done[l] = true;
        // An empty segment: later triangles no longer accept this lane, so
        // they skip the settling loop unless they block an open lane.
        tNear[l] = std::numeric_limits<float>::infinity();
        --open;
    };
    // Inlined at both call sites, as intersectPacket's, so the lane loop stays vectorised.
    const auto visit = [&](std::uint32_t primitive) __attribute__((always_inline)) {
        if (primitives_->sphere(primitive)) {
            for (std::size_t l = 0; l < n; ++l) {
                const Ray& ray = rays[lanes[l]];
                if (!done[l] && primitives_->occludes(primitive, ray, WatertightRay(ray))) settle(l);
            }
            return open == 0;
        }
        const GridPrimitives::TriangleCoordinates& p = primitives_->triangleCoordinates(primitive);
        const float p0x = p[kx], p0y = p[ky], p0z = p[kz];
        const float p1x = p[3 + kx], p1y = p[3 + ky], p1z = p[3 + kz];
        const float p2x = p[6 + kx], p2y = p[6 + ky], p2z = p[6 + kz];
        // The watertight test's float path, lane by lane (watertightLane),
        // the corners made relative to each lane's own origin.
        int anyToSettle = 0;
        for (std::size_t l = 0; l < kLanes; ++l) {
            const WatertightLane lane =
                watertightLane(p0x - ox[l], p0y - oy[l], p0z - oz[l], p1x - ox[l], p1y - oy[l], p1z - oz[l],
                               p2x - ox[l], p2y - oy[l], p2z - oz[l], sx[l], sy[l], sz[l], tNear[l], tFar[l]);
            zeroEdge[l] = static_cast<int>(lane.zeroEdge);
            accepted[l] = static_cast<int>(lane.accepted);
            anyToSettle |= zeroEdge[l] | accepted[l];
        }
        // Most triangles of a cell block no lane: nothing to settle.
        if (!anyToSettle) return false;
        for (std::size_t l = 0; l < n; ++l) {
            if (done[l]) continue;
            if (zeroEdge[l]) {
                // An edge value of exactly zero: the double-precision path, as the scalar test.
                const Ray& ray = rays[lanes[l]];
                if (primitives_->occludes(primitive, ray, WatertightRay(ray))) settle(l);
            } else if (accepted[l]) {
                settle(l);
            }
        }
        return open == 0;
    };
    bool finished = false;
    if (walk.nearPart)
        for (const std::uint32_t p : nearZone_)
            if ((finished = visit(p))) break;
    // Every primitive of every cell a lane visits is tested for it (the walk
    // covers each lane's slices); testing one beyond a lane's segment cannot
    // block it, since the test keeps to the lane's own tNear..tFar.
    // A primitive whose planar box misses every lane's is skipped, as in
    // intersectPacket (most of a cell's triangles block no lane).
    const auto visitCell = [&](std::uint32_t primitive) __attribute__((always_inline)) {
        return missesRange(primitive, walk.planar) ? false : visit(primitive);
    };
    if (!finished && walk.gridPart) walkCells(walk, visitCell, [](int) { return false; });
    for (std::size_t l = 0; l < n; ++l) blocked[lanes[l]] = done[l] ? 1 : 0;
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
