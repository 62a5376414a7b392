#include "bench/GridAgreement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "render/CameraRays.h"
#include "render/LocalShading.h"
#include "render/SurfacePoint.h"
#include "trace/TraceScene.h"
#include "trace/grids/GridAccelerator.h"
#include "trace/grids/GridPrimitives.h"
#include "trace/grids/WatertightTriangle.h"

namespace raycache {

namespace {

bool closeDistances(float a, float b) {
    return std::fabs(a - b) <= 1e-5f * std::max(std::fabs(a), std::fabs(b));
}

bool atEdge(float u, float v) { return std::min({u, v, 1.0f - u - v}) < 1e-4f; }

bool isSphere(const Scene& scene, int object) {
    return std::holds_alternative<Sphere>(scene.objects[static_cast<std::size_t>(object)].shape);
}

// The camera ray of every pixel, row by row.
std::vector<Ray> everyCameraRay(const Camera& camera, int width, int height) {
    const CameraRays cameraRays(camera, width, height);
    std::vector<Ray> rays;
    rays.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) rays.push_back(cameraRays.ray(x, y));
    return rays;
}

// Shadow rays and the light each goes to.
struct ShadowRays {
    std::vector<Ray> rays;
    std::vector<int> lights;
};

// Both tracers' first hits of `rays`, classified; Embree's hits go to `embreeHits`.
PrimaryAgreement comparePrimaryHits(const Scene& scene, const TraceScene& grids, const TraceScene& embree,
                                    const std::vector<Ray>& rays, std::vector<TraceHit>& embreeHits) {
    std::vector<TraceHit> gridHits(rays.size());
    embreeHits.assign(rays.size(), TraceHit{});
    // Batches of one 16-pixel row segment, as the tile kernel's packets would be.
    for (std::size_t base = 0; base < rays.size(); base += 256) {
        const std::size_t n = std::min<std::size_t>(256, rays.size() - base);
        grids.intersectPrimary(std::span(rays).subspan(base, n), std::span(gridHits).subspan(base, n));
        embree.intersectCoherent(std::span(rays).subspan(base, n), std::span(embreeHits).subspan(base, n));
    }
    PrimaryAgreement p;
    p.rays = rays.size();
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const TraceHit& g = gridHits[i];
        const TraceHit& e = embreeHits[i];
        if (g.hit() != e.hit()) {
            const TraceHit& h = g.hit() ? g : e;
            if (!isSphere(scene, h.objectId) && atEdge(h.u, h.v)) ++p.edgeGrazes;
            else ++p.mismatches;
            continue;
        }
        if (!g.hit() || (g.objectId == e.objectId && g.primitiveId == e.primitiveId && closeDistances(g.t, e.t))) {
            ++p.same;
            continue;
        }
        // Different primitives as near as each other (shared edges and vertices, coplanar overlaps).
        if (closeDistances(g.t, e.t)) {
            ++p.ties;
            continue;
        }
        // Different distances: one tracer slipped through an edge (Embree's kernel is not watertight)
        // and saw what lies behind, when the nearer of the two hits is at a triangle edge.
        const TraceHit& nearer = g.t < e.t ? g : e;
        if (!isSphere(scene, nearer.objectId) && atEdge(nearer.u, nearer.v)) ++p.edgeGrazes;
        else ++p.mismatches;
    }
    return p;
}

// Shadow rays from Embree's hits, so both tracers answer the same queries.
ShadowRays shadowRaysOf(const Scene& scene, const std::vector<Ray>& rays, const std::vector<TraceHit>& hits) {
    const LocalShading shading(scene);
    ShadowRays shadows;
    std::vector<ShadowQuery> queries(scene.lights.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const TraceHit& e = hits[i];
        if (!e.hit()) continue;
        const SceneObject& object = scene.objects[static_cast<std::size_t>(e.objectId)];
        const SurfacePoint sp = surfacePointAt(object, rays[i], e, false);
        const int count = shading.shadowQueries(sp, queries.data());
        for (int q = 0; q < count; ++q) {
            shadows.rays.push_back(queries[static_cast<std::size_t>(q)].ray);
            shadows.lights.push_back(queries[static_cast<std::size_t>(q)].lightIndex);
        }
    }
    return shadows;
}

// Whether every occluder of `ray` that the grids' own test sees is met at an
// edge (or at an end of the segment): where the tracers may disagree.
bool occludersAllAtEdges(const GridPrimitives& primitives, const Ray& ray) {
    const WatertightRay wr(ray);
    for (std::uint32_t prim = 0; prim < primitives.count(); ++prim) {
        if (primitives.sphere(prim)) {
            if (primitives.occludes(prim, ray, wr)) return false;
            continue;
        }
        Vec3 p0, p1, p2;
        primitives.triangle(prim, p0, p1, p2);
        WatertightRay wide = wr;  // a little past both ends, to see occluders the segment ends at
        wide.tNear = ray.tNear - 1e-4f * std::max(1.0f, ray.tNear);
        if (std::isfinite(wide.tFar)) wide.tFar *= 1.0001f;
        TriangleHit hit;
        if (intersectWatertight(wide, p0, p1, p2, hit)) {
            const bool nearEnd = std::fabs(hit.t - ray.tNear) <= 1e-4f * std::max(1.0f, hit.t) ||
                                 (std::isfinite(ray.tFar) && std::fabs(hit.t - ray.tFar) <= 1e-4f * ray.tFar);
            if (!atEdge(hit.u, hit.v) && !nearEnd) return false;
        }
    }
    return true;
}

ShadowAgreement compareShadows(const TraceScene& grids, const TraceScene& embree, const GridPrimitives& primitives,
                               const ShadowRays& shadows) {
    const std::vector<Ray>& rays = shadows.rays;
    std::vector<unsigned char> gridBlocked(rays.size()), embreeBlocked(rays.size());
    for (std::size_t base = 0; base < rays.size(); base += 256) {
        const std::size_t n = std::min<std::size_t>(256, rays.size() - base);
        grids.occludedPrimaryShadows(std::span(rays).subspan(base, n), std::span(shadows.lights).subspan(base, n),
                                     std::span(gridBlocked).subspan(base, n));
        embree.occludedCoherent(std::span(rays).subspan(base, n), std::span(embreeBlocked).subspan(base, n));
    }
    ShadowAgreement s;
    s.rays = rays.size();
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (gridBlocked[i] == embreeBlocked[i]) ++s.same;
        else if (occludersAllAtEdges(primitives, rays[i])) ++s.edgeGrazes;
        else ++s.mismatches;
    }
    return s;
}

bool sameHit(const TraceHit& a, const TraceHit& b) {
    return a.objectId == b.objectId && a.primitiveId == b.primitiveId && a.t == b.t && a.u == b.u && a.v == b.v;
}

// The grids' camera-ray answers, in packets of 256 rays (as TraceScene hands
// them over) and ray by ray, against each other and against every primitive.
std::uint64_t primaryBruteForceDifferences(const GridAccelerator& direct, const GridPrimitives& primitives,
                                           const std::vector<Ray>& rays) {
    std::uint64_t differences = 0;
    std::vector<TraceHit> batchHits(rays.size());
    std::vector<unsigned char> refusedRays(rays.size());
    for (std::size_t base = 0; base < rays.size(); base += 256) {
        const std::size_t n = std::min<std::size_t>(256, rays.size() - base);
        direct.intersectPrimaryBatch(std::span(rays).subspan(base, n), std::span(batchHits).subspan(base, n),
                                     std::span(refusedRays).subspan(base, n));
    }
    for (std::size_t i = 0; i < rays.size(); ++i) {
        TraceHit fromGrid;
        if (!direct.intersectPrimary(rays[i], fromGrid)) continue;
        if (refusedRays[i] || !sameHit(batchHits[i], fromGrid)) ++differences;
        TraceHit best;
        const WatertightRay wr(rays[i]);
        for (std::uint32_t prim = 0; prim < primitives.count(); ++prim) primitives.intersect(prim, rays[i], wr, best);
        if (!sameHit(best, fromGrid)) ++differences;
    }
    return differences;
}

// The grids' shadow-ray answers, as packets light by light in batches of
// 256 and ray by ray, against each other and against every primitive.
std::uint64_t shadowBruteForceDifferences(const GridAccelerator& direct, const GridPrimitives& primitives,
                                          const ShadowRays& shadows) {
    const std::vector<Ray>& rays = shadows.rays;
    const std::vector<int>& lights = shadows.lights;
    std::uint64_t differences = 0;
    std::vector<unsigned char> batchBlocked(rays.size()), refusedShadows(rays.size());
    for (std::size_t base = 0; base < rays.size();) {
        std::size_t end = base + 1;
        while (end < rays.size() && end - base < 256 && lights[end] == lights[base]) ++end;
        direct.occludedShadowBatch(std::span<const Ray>(rays).subspan(base, end - base), lights[base],
                                   std::span(batchBlocked).subspan(base, end - base),
                                   std::span(refusedShadows).subspan(base, end - base));
        base = end;
    }
    for (std::size_t i = 0; i < rays.size(); ++i) {
        bool fromGrid = false;
        const bool covered = direct.occludedShadow(rays[i], lights[i], fromGrid);
        if (covered == static_cast<bool>(refusedShadows[i]) || (covered && fromGrid != static_cast<bool>(batchBlocked[i])))
            ++differences;
        if (!covered) continue;
        const WatertightRay wr(rays[i]);
        bool blocked = false;
        for (std::uint32_t prim = 0; prim < primitives.count() && !blocked; ++prim)
            blocked = primitives.occludes(prim, rays[i], wr);
        if (blocked != fromGrid) ++differences;
    }
    return differences;
}

}  // namespace

GridAgreement compareGridsWithEmbree(const Scene& scene, const Camera& camera, int width, int height,
                                     const Parallel& parallel, bool bruteForce) {
    GridAgreement result;
    TraceOptions gridOptions;
    gridOptions.accelerator = Accelerator::Grids;
    const TraceScene grids(scene, gridOptions);
    const TraceScene embree(scene);
    grids.prepareFrame(scene, camera, width, height, parallel);
    const GridPrimitives primitives(scene, parallel);

    const std::vector<Ray> rays = everyCameraRay(camera, width, height);
    std::vector<TraceHit> embreeHits;
    result.primary = comparePrimaryHits(scene, grids, embree, rays, embreeHits);
    const ShadowRays shadows = shadowRaysOf(scene, rays, embreeHits);
    result.shadow = compareShadows(grids, embree, primitives, shadows);
    const FrameTraceStats stats = grids.frameStats();
    result.primary.refused = stats.primaryRefused;
    result.shadow.refused = stats.shadowRefused;
    result.lightsWithSixFaces = stats.build.lightsWithSixFaces;

    if (bruteForce) {
        // The grids themselves (no Embree behind them) against every primitive, on the rays they answer.
        result.bruteForceChecked = true;
        GridAccelerator direct(gridOptions.grids);
        direct.buildFrame(scene, camera, width, height, parallel);
        result.bruteForceDifferences = primaryBruteForceDifferences(direct, primitives, rays) +
                                       shadowBruteForceDifferences(direct, primitives, shadows);
    }
    return result;
}

}  // namespace raycache
