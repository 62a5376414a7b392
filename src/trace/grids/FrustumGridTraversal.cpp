// FrustumGrid: rays through the grid. The cells a ray visits (its
// traversal), and the queries that walk them: one ray at a time, or a batch
// gathered into packets of up to 16 lanes. One file because GCC resolves a
// target_clones function (generalTraversals, intersectPacket,
// occludedPacket) in every translation unit that calls it, against clones
// that only its own defines: its callers must live with it.
#include "trace/grids/FrustumGrid.h"

#include <algorithm>
#include <array>
#include <limits>

#include "core/DoubleLanes.h"

namespace raycache {

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

}  // namespace raycache
