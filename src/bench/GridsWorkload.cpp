#include "bench/GridsWorkload.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "core/Elapsed.h"
#include "render/CameraRays.h"
#include "render/LocalShading.h"
#include "render/SurfacePoint.h"
#include "scene/MeshGenerators.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

constexpr int kTile = 16;

}  // namespace

GridsModel gridsTorusModel(int triangles) {
    const int tube = std::max(8, static_cast<int>(std::sqrt(triangles / 4.0)));
    const int ring = std::max(8, triangles / (2 * tube));
    Scene s;
    auto mesh = std::make_shared<TriangleMesh>(makeTorus(0.35f, 0.15f, ring, tube));
    for (Vec3& p : mesh->positions) p = p * 3.0f;
    SceneObject torus;
    torus.name = "torus";
    torus.shape = MeshShape{mesh};
    s.objects.push_back(torus);
    auto floor = std::make_shared<TriangleMesh>(makePlane());
    for (Vec3& p : floor->positions) p = p * 10.0f + Vec3{0.0f, -1.0f, 0.0f};
    SceneObject f;
    f.name = "floor";
    f.shape = MeshShape{floor};
    s.objects.push_back(f);
    Light light;
    light.position = {2.0f, 6.0f, 3.0f};
    s.lights.push_back(light);
    s.camera = Camera{{0.0f, 2.5f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f};
    s.cameraPath.kind = CameraPathKind::Orbit;
    s.cameraPath.center = {0.0f, 0.0f, 0.0f};
    s.cameraPath.degreesPerFrame = 2.0f;
    const std::size_t count = mesh->triangles.size() + floor->triangles.size();
    return {"torus " + std::to_string((count + 500) / 1000) + "k", std::move(s), false};
}

GridsFrameRays cameraRaysByTile(const Camera& camera, int side) {
    GridsFrameRays rays;
    const CameraRays cameraRays(camera, side, side);
    for (int y0 = 0; y0 < side; y0 += kTile)
        for (int x0 = 0; x0 < side; x0 += kTile) {
            const TileRange tile{x0, y0, std::min(side, x0 + kTile), std::min(side, y0 + kTile)};
            rays.tiles.push_back(tile);
            std::vector<Ray> tileRays;
            for (int y = tile.y0; y < tile.y1; ++y)
                for (int x = tile.x0; x < tile.x1; ++x) tileRays.push_back(cameraRays.ray(x, y));
            rays.primary.push_back(std::move(tileRays));
        }
    return rays;
}

double rebuildOpponent(std::optional<TraceScene>& kept, const Scene& still, const TraceOptions& options) {
    const auto start = Clock::now();
    if (kept)
        kept->rebuild(still);
    else
        kept.emplace(still, options);
    return millisecondsSince(start);
}

double tracePrimary(const TraceScene& tracer, const GridsFrameRays& rays, const Parallel& parallel, bool grids,
                    std::vector<std::vector<TraceHit>>* keepHits) {
    // The answers' memory is made before the clock starts: a renderer keeps
    // its buffers from frame to frame, and fresh pages (20 MB at 1024²) would
    // add the kernel's page faults to both tracers' times.
    std::vector<std::vector<TraceHit>> hits(rays.tiles.size());
    for (std::size_t i = 0; i < hits.size(); ++i) hits[i].resize(rays.primary[i].size());
    const auto start = Clock::now();
    parallel.forEachIndex(static_cast<int>(rays.tiles.size()), [&](int t, int) {
        const auto i = static_cast<std::size_t>(t);
        if (grids)
            tracer.intersectPrimary(rays.primary[i], hits[i]);
        else
            tracer.intersectCoherent(rays.primary[i], hits[i]);
    });
    const double ms = millisecondsSince(start);
    if (keepHits) *keepHits = std::move(hits);
    return ms;
}

double traceShadows(const TraceScene& tracer, const GridsFrameRays& rays, const Parallel& parallel, bool grids) {
    // As tracePrimary: the answers' memory is made before the clock starts.
    std::vector<std::vector<unsigned char>> blocked(rays.tiles.size());
    for (std::size_t i = 0; i < blocked.size(); ++i) blocked[i].resize(rays.shadow[i].size());
    const auto start = Clock::now();
    parallel.forEachIndex(static_cast<int>(rays.tiles.size()), [&](int t, int) {
        const auto i = static_cast<std::size_t>(t);
        if (grids)
            tracer.occludedPrimaryShadows(rays.shadow[i], rays.lights[i], blocked[i]);
        else
            tracer.occludedCoherent(rays.shadow[i], blocked[i]);
    });
    return millisecondsSince(start);
}

void addShadowRays(const Scene& scene, const std::vector<std::vector<TraceHit>>& hits, GridsFrameRays& rays) {
    const LocalShading shading(scene);
    std::vector<ShadowQuery> queries(scene.lights.size());
    rays.shadow.assign(rays.tiles.size(), {});
    rays.lights.assign(rays.tiles.size(), {});
    for (std::size_t t = 0; t < rays.tiles.size(); ++t)
        for (std::size_t i = 0; i < hits[t].size(); ++i) {
            const TraceHit& h = hits[t][i];
            if (!h.hit()) continue;
            const SurfacePoint sp =
                surfacePointAt(scene.objects[static_cast<std::size_t>(h.objectId)], rays.primary[t][i], h, false);
            const int count = shading.shadowQueries(sp, queries.data());
            for (int q = 0; q < count; ++q) {
                rays.shadow[t].push_back(queries[static_cast<std::size_t>(q)].ray);
                rays.lights[t].push_back(queries[static_cast<std::size_t>(q)].lightIndex);
            }
        }
}

}  // namespace raycache
