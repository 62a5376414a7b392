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

    const CameraRays cameraRays(camera, width, height);
    std::vector<Ray> rays;
    rays.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) rays.push_back(cameraRays.ray(x, y));
    std::vector<TraceHit> gridHits(rays.size()), embreeHits(rays.size());
    // Batches of one 16-pixel row segment, as the tile kernel's packets would be.
    for (std::size_t base = 0; base < rays.size(); base += 256) {
        const std::size_t n = std::min<std::size_t>(256, rays.size() - base);
        grids.intersectPrimary(std::span(rays).subspan(base, n), std::span(gridHits).subspan(base, n));
        embree.intersectCoherent(std::span(rays).subspan(base, n), std::span(embreeHits).subspan(base, n));
    }
    PrimaryAgreement& p = result.primary;
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

    // Shadow rays from Embree's hits, so both tracers answer the same queries.
    const LocalShading shading(scene);
    std::vector<Ray> shadowRays;
    std::vector<int> lights;
    std::vector<ShadowQuery> queries(scene.lights.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const TraceHit& e = embreeHits[i];
        if (!e.hit()) continue;
        const SceneObject& object = scene.objects[static_cast<std::size_t>(e.objectId)];
        const SurfacePoint sp = surfacePointAt(object, rays[i], e, false);
        const int count = shading.shadowQueries(sp, queries.data());
        for (int q = 0; q < count; ++q) {
            shadowRays.push_back(queries[static_cast<std::size_t>(q)].ray);
            lights.push_back(queries[static_cast<std::size_t>(q)].lightIndex);
        }
    }
    std::vector<unsigned char> gridBlocked(shadowRays.size()), embreeBlocked(shadowRays.size());
    for (std::size_t base = 0; base < shadowRays.size(); base += 256) {
        const std::size_t n = std::min<std::size_t>(256, shadowRays.size() - base);
        grids.occludedPrimaryShadows(std::span(shadowRays).subspan(base, n), std::span(lights).subspan(base, n),
                                     std::span(gridBlocked).subspan(base, n));
        embree.occludedCoherent(std::span(shadowRays).subspan(base, n), std::span(embreeBlocked).subspan(base, n));
    }
    ShadowAgreement& s = result.shadow;
    s.rays = shadowRays.size();
    for (std::size_t i = 0; i < shadowRays.size(); ++i) {
        if (gridBlocked[i] == embreeBlocked[i]) {
            ++s.same;
            continue;
        }
        // Which occluders does our test see, and are they all met at an edge?
        bool allAtEdges = true;
        const WatertightRay wr(shadowRays[i]);
        for (std::uint32_t prim = 0; prim < primitives.count() && allAtEdges; ++prim) {
            if (primitives.sphere(prim)) {
                if (primitives.occludes(prim, shadowRays[i], wr)) allAtEdges = false;
                continue;
            }
            Vec3 p0, p1, p2;
            primitives.triangle(prim, p0, p1, p2);
            WatertightRay wide = wr;  // a little past both ends, to see occluders the segment ends at
            wide.tNear = shadowRays[i].tNear - 1e-4f * std::max(1.0f, shadowRays[i].tNear);
            if (std::isfinite(wide.tFar)) wide.tFar *= 1.0001f;
            TriangleHit hit;
            if (intersectWatertight(wide, p0, p1, p2, hit)) {
                const bool nearEnd = std::fabs(hit.t - shadowRays[i].tNear) <= 1e-4f * std::max(1.0f, hit.t) ||
                                     (std::isfinite(shadowRays[i].tFar) &&
                                      std::fabs(hit.t - shadowRays[i].tFar) <= 1e-4f * shadowRays[i].tFar);
                if (!atEdge(hit.u, hit.v) && !nearEnd) allAtEdges = false;
            }
        }
        if (allAtEdges) ++s.edgeGrazes;
        else ++s.mismatches;
    }
    const FrameTraceStats stats = grids.frameStats();
    p.refused = stats.primaryRefused;
    s.refused = stats.shadowRefused;
    result.lightsWithSixFaces = stats.build.lightsWithSixFaces;

    if (bruteForce) {
        // The grids themselves (no Embree behind them) against every primitive, on the rays they answer.
        result.bruteForceChecked = true;
        GridAccelerator direct(gridOptions.grids);
        direct.buildFrame(scene, camera, width, height, parallel);
        // Packets of 256 rays, as TraceScene hands them over, and each ray alone.
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
            const TraceHit& b = batchHits[i];
            if (refusedRays[i] || b.objectId != fromGrid.objectId || b.primitiveId != fromGrid.primitiveId ||
                b.t != fromGrid.t || b.u != fromGrid.u || b.v != fromGrid.v)
                ++result.bruteForceDifferences;
            TraceHit best;
            const WatertightRay wr(rays[i]);
            for (std::uint32_t prim = 0; prim < primitives.count(); ++prim) primitives.intersect(prim, rays[i], wr, best);
            if (best.objectId != fromGrid.objectId || best.primitiveId != fromGrid.primitiveId || best.t != fromGrid.t ||
                best.u != fromGrid.u || best.v != fromGrid.v)
                ++result.bruteForceDifferences;
        }
        // Shadow rays as packets, light by light in batches of 256, against each ray alone.
        std::vector<unsigned char> batchBlocked(shadowRays.size()), refusedShadows(shadowRays.size());
        for (std::size_t base = 0; base < shadowRays.size();) {
            std::size_t end = base + 1;
            while (end < shadowRays.size() && end - base < 256 && lights[end] == lights[base]) ++end;
            direct.occludedShadowBatch(std::span<const Ray>(shadowRays).subspan(base, end - base), lights[base],
                                       std::span(batchBlocked).subspan(base, end - base),
                                       std::span(refusedShadows).subspan(base, end - base));
            base = end;
        }
        for (std::size_t i = 0; i < shadowRays.size(); ++i) {
            bool fromGrid = false;
            const bool covered = direct.occludedShadow(shadowRays[i], lights[i], fromGrid);
            if (covered == static_cast<bool>(refusedShadows[i]) || (covered && fromGrid != static_cast<bool>(batchBlocked[i])))
                ++result.bruteForceDifferences;
            if (!covered) continue;
            const WatertightRay wr(shadowRays[i]);
            bool blocked = false;
            for (std::uint32_t prim = 0; prim < primitives.count() && !blocked; ++prim)
                blocked = primitives.occludes(prim, shadowRays[i], wr);
            if (blocked != fromGrid) ++result.bruteForceDifferences;
        }
    }
    return result;
}

}  // namespace raycache
