#pragma once
// A grid over a frustum, rebuilt every frame (Guntury and Narayanan 2010): cells are a regular
// nx x ny lattice of the frame's 2D grid coordinates (s, t) (GridFrame.h)
// times nz slices of depth z. Built by listing a (cell, primitive) pair for
// every cell a primitive's conservative bounds overlap, sorting the pairs by
// cell with a parallel radix sort, and scanning the sorted keys for each
// cell's range. Used with a perspective frame for primary rays and with the
// angular or orthographic frames of lights for shadow rays.
//
// Exactness: a ray is answered only when the grid covers its whole segment
// (every part of it inside the rectangle of cells, or in the near zone of a
// perspective grid, or where no geometry is); then every primitive it can
// meet is in one of the cells it visits, with a margin far above the
// rounding of the bounds. A ray the grid does not cover is refused, and the
// caller answers it another way (trace/TraceScene.cpp: Embree, counted).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/Parallel.h"
#include "core/Ray.h"
#include "trace/TraceHit.h"
#include "trace/grids/CellLists.h"
#include "trace/grids/GridAxis.h"
#include "trace/grids/GridFrame.h"
#include "trace/grids/GridPrimitives.h"

namespace raycache {

// FrustumGrid's lane loops, one copy per lane level up to AVX2
// (FrustumGridBuildKernels.inc, FrustumGridTraversalKernels.inc).
namespace avx2 {
struct FrustumGridBuildKernels;
struct FrustumGridTraversalKernels;
}  // namespace avx2
namespace baseline {
struct FrustumGridBuildKernels;
struct FrustumGridTraversalKernels;
}  // namespace baseline

// A box in frame coordinates.
struct FrameBox {
    Point3d lo, hi;
};

struct FrustumGridSpec {
    GridFrame frame;
    double s0 = -1.0, s1 = 1.0, t0 = -1.0, t1 = 1.0;  // the rectangle of cells, in grid coordinates
    // Perspective frames: the slices start here; what lies nearer (toward
    // the apex) is the near zone, whose primitives every ray tests.
    double zNear = 0.0;
    // Where rays may run at z < zNear (frame coordinates). Rays that leave it
    // there are refused.
    FrameBox nearZone;
    // The slices end at min(zFarLimit, the farthest geometry).
    double zFarLimit = 1e300;
    int nx = 1, ny = 1;
    // Slices: about cellsPerPrimitive cells per primitive in the rectangle, at most maxSlices.
    double cellsPerPrimitive = 2.0;
    int maxSlices = 64;
    // When more than this many slices would be needed, the columns are made
    // finer instead (at most kMaxColumnRefinement times across each axis),
    // so a ray crosses fewer cells (0: nx x ny columns always). Light grids:
    // their shadow rays cross every slice between their origin and the light.
    int refineAboveSlices = 0;
    // Positional margin in world units added around every primitive's
    // bounds; covers the rounding of the float intersection tests.
    double margin = 1e-5;
};

struct FrustumGridStats {
    std::uint64_t primitivesBinned = 0;  // primitives with at least one cell
    std::uint64_t pairs = 0;             // (cell, primitive) pairs sorted
    std::uint64_t nearZone = 0;          // primitives every ray tests
    int nx = 0, ny = 0, nz = 0;
};

// The primitives a grid is built over may be narrowed to candidates: those
// whose byte in `masks` has `bit` set. A primitive left out must be one no
// ray the grid covers can meet (GridAccelerator: the face grids of a light
// among the geometry). No masks: every primitive.
struct PrimitiveFilter {
    std::span<const std::uint8_t> masks;
    std::uint8_t bit = 0;
    bool admits(std::uint32_t primitive) const { return masks.empty() || (masks[primitive] & bit) != 0; }
};

class FrustumGrid {
public:
    // Rebuilds the grid over `primitives` (which must outlive the queries),
    // or over the candidates among them.
    void build(const FrustumGridSpec& spec, const GridPrimitives& primitives, const Parallel& parallel,
               PrimitiveFilter filter = {});

    // Nearest hit, as TraceScene::intersect. False: the ray is not covered (`hit` untouched).
    bool intersect(const Ray& ray, TraceHit& hit) const;
    // Nearest hits of a batch, hits[i] for rays[i]; refused[i] = 1 for the
    // rays the grid does not cover (their hits untouched). Rays that share
    // an origin, a shear axis and a traversal (a tile's camera rays, column
    // by column) are traced as packets of up to 16 lanes, the lanes' loop of
    // the watertight test vectorised; the answers are bit for bit those of
    // intersect().
    void intersectBatch(std::span<const Ray> rays, std::span<TraceHit> hits, std::span<unsigned char> refused) const;
    // Any hit in the segment. False: the ray is not covered.
    bool occluded(const Ray& ray, bool& blocked) const;
    // Any-hit answers of a batch, blocked[i] for rays[i]; refused[i] = 1 for
    // the rays the grid does not cover (blocked[i] then 0). Rays that share
    // a shear axis and a column range (a light tile's shadow rays: in the
    // light's frame they run along its radial lines) are traced as packets
    // of up to 16 lanes over the union of their slices, each with its own
    // origin; the answers are those of occluded().
    void occludedBatch(std::span<const Ray> rays, std::span<unsigned char> blocked,
                       std::span<unsigned char> refused) const;

    // Points whose hull holds the part of every column between its first
    // and last occupied slice, hence every point a ray could hit in the
    // grid: per corner of the columns' lattice, the nearest and farthest
    // such depth along its line from the apex. Perspective grids only.
    std::vector<Vec3> occupiedColumnCorners() const;

    const FrustumGridStats& stats() const { return stats_; }
    const FrustumGridSpec& spec() const { return spec_; }

private:
    friend struct avx2::FrustumGridBuildKernels;
    friend struct avx2::FrustumGridTraversalKernels;
    friend struct baseline::FrustumGridBuildKernels;
    friend struct baseline::FrustumGridTraversalKernels;

    // A range of planar grid coordinates (s, t: x/z and y/z, or x and y);
    // empty until something is added.
    struct PlanarRange {
        double sLo = std::numeric_limits<double>::infinity(), sHi = -std::numeric_limits<double>::infinity();
        double tLo = std::numeric_limits<double>::infinity(), tHi = -std::numeric_limits<double>::infinity();
        void add(const PlanarRange& other) {
            sLo = std::min(sLo, other.sLo);
            sHi = std::max(sHi, other.sHi);
            tLo = std::min(tLo, other.tLo);
            tHi = std::max(tHi, other.tHi);
        }
    };
    struct CellRange {
        int i0, i1, j0, j1, k0, k1;  // inclusive; i1 < i0 when the primitive has no cell
    };
    static constexpr CellRange kNoCells{0, -1, 0, -1, 0, -1};
    static constexpr double kFrustumInfinity = std::numeric_limits<double>::infinity();
    // A camera packet's key: its column (i, j), whether it crosses the near
    // zone, and its shear axes (kz, then kx; ky follows), in one integer.
    static constexpr int kColumnBits = 24;
    static constexpr std::uint64_t kColumnMask = (std::uint64_t{1} << kColumnBits) - 1;
    // A binned primitive's planar box: its projected box (margin included)
    // within the rectangle, rounded outward to float. A packet skips a
    // primitive whose box misses every lane's planar range.
    struct PlanarBox {
        float sLo, sHi, tLo, tHi;
    };
    // The cells and planar box of a primitive whose planar box is sLo..tHi
    // (overlapping the rectangle) and depth range zA..zB.
    [[gnu::always_inline]] CellRange cellRangeOf(double sLo, double sHi, double tLo, double tHi, double zA, double zB,
                                                 PlanarBox& box) const;
    // Whether `primitive`'s planar box misses `range`: then no ray whose
    // segment's part in the grid projects into `range` can meet it there
    // (the box holds the projection of every point of the primitive at
    // z >= the first slice, by the margin).
    bool missesRange(std::uint32_t primitive, const PlanarRange& range) const {
        const PlanarBox& b = boxes_[primitive];
        return b.sHi < range.sLo || b.sLo > range.sHi || b.tHi < range.tLo || b.tLo > range.tHi;
    }
    // The part of a ray's segment the grid must cover, in ray parameter t.
    struct Traversal {
        bool covered = true;
        bool nearPart = false, gridPart = false;
        int i0 = 0, i1 = -1, j0 = 0, j1 = -1, k0 = 0, k1 = -1;
        bool ascending = true;
        Point3d origin, direction;  // frame coordinates
        // The planar range of the segment's part in the grid (s and t are
        // monotonic along a segment: its ends' values bound it).
        PlanarRange planar;
    };
    Traversal traversalOf(const Ray& ray) const;
    // The column of a ray from the apex of a perspective grid whose segment
    // spans every slice (a camera ray): the column of its direction; it
    // visits all the column's slices (apexWalk). `d`: the direction in
    // frame coordinates. `column` holds a first guess (a neighbour's column)
    // on entry. False: not such a ray; generalTraversal decides.
    struct ApexColumn {
        int i = 0, j = 0;
        bool nearPart = false;
    };
    bool apexColumn(const Ray& ray, Point3d& d, ApexColumn& column) const;
    Traversal apexWalk(const ApexColumn& column) const;
    // Any ray. `hint`: a column to look for the ray's from (a neighbour's;
    // negative: none); the cells found do not depend on it.
    struct ColumnHint {
        int i = -1, j = -1;
    };
    // The traversals of the first kDoubleLanes (4) of `rays` at once, into
    // out[0..]: each quantity of the lanes is one vector (core/DoubleLanes.h),
    // so four rays cost about what one did in scalar code. `hint` is updated
    // to the last covered ray's column. Runs the lane level's copy
    // (FrustumGridTraversalKernels.inc).
    void generalTraversals(std::span<const Ray> rays, Traversal* out, ColumnHint& hint) const;
    Traversal generalTraversal(const Ray& ray, ColumnHint hint) const {
        Traversal tr;
        generalTraversals(std::span<const Ray>(&ray, 1), &tr, hint);
        return tr;
    }
    // A camera packet's key (column and shear axes in one integer), and the column back from it.
    static std::uint64_t cameraKey(const ApexColumn& column, const Vec3& direction);
    static ApexColumn unpackCameraKey(std::uint64_t key);
    // The packets run the lane level's copy (FrustumGridTraversalKernels.inc).
    // `lanesPlanar`: the union of the lanes' planar ranges in the grid part;
    // null for rays from the apex (apexWalk), whose planar coordinates are
    // their directions'.
    void intersectPacket(std::span<const Ray> rays, std::span<const std::uint32_t> lanes, const Traversal& tr,
                         const PlanarRange* lanesPlanar, std::span<TraceHit> hits) const;
    // `walk`: the union of the lanes' traversals (same columns, every slice
    // any of them visits, the union of their planar ranges).
    void occludedPacket(std::span<const Ray> rays, std::span<const std::uint32_t> lanes, const Traversal& walk,
                        std::span<unsigned char> blocked) const;
    CellRange binPrimitive(std::uint32_t primitive, bool& inNearZone, PlanarBox& box) const;
    // ranges_, boxes_ and nearFlags_ of primitives first .. first + count - 1
    // (count <= kDoubleLanes), as binPrimitive gives them, the triangles'
    // arithmetic four at a time (core/DoubleLanes.h). Runs the lane level's
    // copy (FrustumGridBuildKernels.inc).
    void binPrimitives(std::uint32_t first, std::uint32_t count, PrimitiveFilter filter, std::uint64_t& pairs,
                       std::uint32_t& binned);
    // Index of cell (i, j) of depth slice k in cellLists_. A column's slices
    // lie next to one another: a ray walks one column front to back.
    std::size_t flatCell(int k, int j, int i) const {
        return (static_cast<std::size_t>(j) * static_cast<std::size_t>(spec_.nx) + static_cast<std::size_t>(i)) *
                   static_cast<std::size_t>(nz_) +
               static_cast<std::size_t>(k);
    }
    // True in the first cell, in the traversal's order, where the ray meets
    // `primitive`: a primitive spanning many cells (a floor, a wall) is
    // tested once per ray, not once per cell. Testing it again would give
    // the same answer.
    bool firstVisit(std::uint32_t primitive, const Traversal& tr, int k, int j, int i) const {
        const CellRange& r = ranges_[primitive];
        const int firstK = tr.ascending ? std::max(r.k0, tr.k0) : std::min(r.k1, tr.k1);
        return k == firstK && j == std::max(r.j0, tr.j0) && i == std::max(r.i0, tr.i0);
    }
    double sliceLower(int k) const { return depthAxis_.boundary(k); }
    // Whether a hit at frame depth `z` ends a front-to-back walk after slice
    // k: a primitive not met yet lies wholly beyond the slice (by the
    // margin), so it cannot be nearer.
    bool hitEndsWalk(const Traversal& tr, double z, int k) const {
        return tr.ascending ? z + spec_.margin <= sliceLower(k + 1) : z - spec_.margin >= sliceLower(k);
    }
    // The grid part of a traversal is walked slice by slice, front to back,
    // by FrustumGridTraversalKernels::walkCells: it is compiled inside each
    // lane level's copy, with the lane loops it inlines.

    FrustumGridSpec spec_;
    const GridPrimitives* primitives_ = nullptr;
    // Whether apexColumn may be used: a perspective grid whose near zone
    // holds the frustum's tip, so a ray from the apex through the rectangle
    // never leaves it before zNear. The apex as the float rays start from.
    bool apexRays_ = false;
    Vec3 apex_;
    double geometryZLo_ = 0.0, geometryZHi_ = -1.0;  // every primitive's depth range (margins included)
    double zLo_ = 0.0, zHi_ = 0.0;
    int nz_ = 1;
    // Columns across (planar s = x/z or x, and t) and slices along depth z.
    GridAxis sAxis_, tAxis_, depthAxis_;
    CellLists cellLists_;  // every cell's primitives
    std::vector<std::uint32_t> nearZone_;
    FrustumGridStats stats_;
    // Reused from frame to frame.
    std::vector<CellRange> ranges_;
    std::vector<PlanarBox> boxes_;  // set for the primitives with cells
    std::vector<unsigned char> nearFlags_;
};

}  // namespace raycache
