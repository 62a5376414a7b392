// FrustumGrid: rays through the grid. The cells a ray visits (its
// traversal), and the queries that walk them: one ray at a time, or a batch
// gathered into packets of up to 16 lanes, whose lane loops are
// FrustumGridTraversalKernels.inc.
#include "trace/grids/FrustumGrid.h"

#include <algorithm>
#include <array>
#include <limits>

#include "core/DoubleLanes.h"
#include "core/FloatLanes.h"
#include "core/LaneLevels.h"

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

#define RAYCACHE_LANE_KERNELS "trace/grids/FrustumGridTraversalKernels.inc"
#define RAYCACHE_LANE_LEVELS_UP_TO_AVX2
#include "core/LaneLevelsInclude.h"

void FrustumGrid::generalTraversals(std::span<const Ray> rays, Traversal* out, ColumnHint& hint) const {
    RAYCACHE_LANE_DISPATCH_UP_TO_AVX2(FrustumGridTraversalKernels::generalTraversals, *this, rays, out, hint);
}

bool FrustumGrid::intersect(const Ray& ray, TraceHit& hit) const {
    RAYCACHE_LANE_DISPATCH_UP_TO_AVX2(FrustumGridTraversalKernels::intersect, *this, ray, hit);
}

bool FrustumGrid::occluded(const Ray& ray, bool& blocked) const {
    RAYCACHE_LANE_DISPATCH_UP_TO_AVX2(FrustumGridTraversalKernels::occluded, *this, ray, blocked);
}

void FrustumGrid::intersectPacket(std::span<const Ray> rays, std::span<const std::uint32_t> lanes, const Traversal& tr,
                                  const PlanarRange* lanesPlanar, std::span<TraceHit> hits) const {
    RAYCACHE_LANE_DISPATCH_UP_TO_AVX2(FrustumGridTraversalKernels::intersectPacket, *this, rays, lanes, tr, lanesPlanar,
                                      hits);
}

void FrustumGrid::occludedPacket(std::span<const Ray> rays, std::span<const std::uint32_t> lanes, const Traversal& walk,
                                 std::span<unsigned char> blocked) const {
    RAYCACHE_LANE_DISPATCH_UP_TO_AVX2(FrustumGridTraversalKernels::occludedPacket, *this, rays, lanes, walk, blocked);
}

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


}  // namespace raycache
