#include "render/DeferredShading.h"

#include <chrono>

#include "render/CameraRays.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Per-worker buffers for one tile's shadow batch, allocated once per frame.
struct ShadowScratch {
    std::vector<std::size_t> pixel;       // G-buffer index of each surface pixel in the tile
    std::vector<Vec3> direction;          // its camera ray direction
    std::vector<SurfacePoint> points;     // its surface
    std::vector<int> firstQuery;          // surface pixel k's queries: [firstQuery[k], firstQuery[k+1])
    std::vector<ShadowQuery> queries;
    std::vector<Ray> shadowRays;
    std::vector<unsigned char> occluded;
    std::vector<unsigned char> visible;
    RayCounts counts;

    ShadowScratch(std::size_t pixels, std::size_t lights)
        : pixel(pixels), direction(pixels), points(pixels), firstQuery(pixels + 1), queries(pixels * lights),
          shadowRays(pixels * lights), occluded(pixels * lights), visible(pixels * lights) {}
};

}  // namespace

SurfacePoint surfacePointFromGBuffer(const Scene& scene, const GBufferView& gbuffer, std::size_t i,
                                     const Vec3& rayDirection) {
    SurfacePoint sp;
    sp.position = gbuffer.position(i);
    sp.normal = gbuffer.normalAt(i);
    const SceneObject& object = scene.objects[static_cast<std::size_t>(gbuffer.objectId(i))];
    if (const auto* shape = std::get_if<MeshShape>(&object.shape)) {
        // The geometric normal comes from the triangle itself, as in surfacePointAt.
        const TriangleMesh& mesh = *shape->mesh;
        const auto& tri = mesh.triangles[static_cast<std::size_t>(gbuffer.primitiveId(i))];
        const Vec3& p0 = mesh.positions[tri[0]];
        Vec3 ng = normalize(cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0));
        if (mesh.normals.empty() || dot(sp.normal, sp.normal) == 0.0f) {
            sp.normal = ng;
        } else if (dot(ng, sp.normal) < 0.0f) {
            ng = -ng;
        }
        sp.geometricNormal = ng;
    } else {
        sp.geometricNormal = sp.normal;
    }
    sp.frontFace = dot(rayDirection, sp.geometricNormal) < 0.0f;
    if (!sp.frontFace) {
        sp.normal = -sp.normal;
        sp.geometricNormal = -sp.geometricNormal;
    }
    return sp;
}

DeferredShading::DeferredShading(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                                 const Parallel& parallel, RayCache* cache)
    : scene_(scene), tracer_(tracer), settings_(settings), parallel_(parallel),
      cache_(cache && !cache->empty() ? cache : nullptr), integrator_(scene, tracer, settings, cache_) {
    needsSecondary_.reserve(scene.objects.size());
    for (const SceneObject& object : scene.objects)
        needsSecondary_.push_back(settings.maxDepth > 1 && (object.material.reflects() || object.material.refracts())
                                      ? 1
                                      : 0);
}

void DeferredShading::shade(const Camera& camera, const GBufferView& gbuffer, Image& film, FrameStats& stats) {
    const int width = settings_.width, height = settings_.height;
    if (film.width() != width || film.height() != height) film = Image(width, height);
    const auto pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    direct_.resize(pixels);
    secondary_.resize(pixels);
    const CameraRays cameraRays(camera, width, height);
    const int tileSize = settings_.tileSize;
    const auto tilePixels = static_cast<std::size_t>(tileSize) * static_cast<std::size_t>(tileSize);
    const auto workers = static_cast<std::size_t>(parallel_.threadCount());
    PhaseTimes& phases = stats.phases.emplace(stats.phases.value_or(PhaseTimes{}));

    // Shadows: the rays of every surface pixel in a tile traced together as
    // packets (they start close to each other and head for the same lights).
    auto start = Clock::now();
    std::vector<ShadowScratch> scratch(workers, ShadowScratch(tilePixels, scene_.lights.size()));
    parallel_.forEachTile(width, height, tileSize, [&](const TileRange& tile, int worker) {
        ShadowScratch& s = scratch[static_cast<std::size_t>(worker)];
        std::size_t n = 0, queryCount = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const std::size_t i = gbuffer.index(x, y);
                if (!gbuffer.hasSurface(i)) continue;
                s.pixel[n] = i;
                s.direction[n] = cameraRays.ray(x, y).direction;
                s.points[n] = surfacePointFromGBuffer(scene_, gbuffer, i, s.direction[n]);
                s.firstQuery[n] = static_cast<int>(queryCount);
                queryCount += static_cast<std::size_t>(integrator_.shadowQueries(s.points[n], s.queries.data() + queryCount));
                ++n;
            }
        s.firstQuery[n] = static_cast<int>(queryCount);
        for (std::size_t q = 0; q < queryCount; ++q) s.shadowRays[q] = s.queries[q].ray;
        tracer_.occludedCoherent(std::span(s.shadowRays.data(), queryCount), std::span(s.occluded.data(), queryCount));
        for (std::size_t q = 0; q < queryCount; ++q) s.visible[q] = s.occluded[q] ? 0 : 1;
        s.counts.shadow += queryCount;
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t i = s.pixel[k];
            const Material& material = scene_.objects[static_cast<std::size_t>(gbuffer.objectId(i))].material;
            const auto first = static_cast<std::size_t>(s.firstQuery[k]);
            const auto count = static_cast<std::size_t>(s.firstQuery[k + 1]) - first;
            direct_[i] = integrator_.directLight(material, gbuffer.albedoAt(i), s.points[k], -s.direction[k],
                                                 std::span(s.queries.data() + first, count),
                                                 std::span(s.visible.data() + first, count));
        }
    });
    for (const ShadowScratch& s : scratch) stats.rays += s.counts;
    phases.shadows += millisecondsSince(start);

    // Secondary: only pixels whose material reflects or refracts, each
    // announced to its cache worker first so cache stores stay ordered by pixel.
    start = Clock::now();
    std::vector<CacheWorker> cacheWorkers;
    if (cache_) {
        cacheWorkers = cache_->makeWorkers(parallel_.threadCount());
        cache_->beginFrame(cacheWorkers);
    }
    std::vector<RayCounts> counts(workers);
    parallel_.forEachTile(width, height, tileSize, [&](const TileRange& tile, int worker) {
        CacheWorker* cacheWorker = cache_ ? &cacheWorkers[static_cast<std::size_t>(worker)] : nullptr;
        PathContext path{counts[static_cast<std::size_t>(worker)], cacheWorker};
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const std::size_t i = gbuffer.index(x, y);
                if (!gbuffer.hasSurface(i)) continue;
                const int objectId = gbuffer.objectId(i);
                if (!needsSecondary_[static_cast<std::size_t>(objectId)]) continue;
                if (cacheWorker) cacheWorker->beginPixel(static_cast<std::uint32_t>(i));
                const Ray ray = cameraRays.ray(x, y);
                const SurfacePoint sp = surfacePointFromGBuffer(scene_, gbuffer, i, ray.direction);
                secondary_[i] = integrator_.secondaryLight(ray, sp, objectId, 1, 1.0f, path);
            }
    });
    for (const RayCounts& c : counts) stats.rays += c;
    if (cache_) stats.cache = cache_->endFrame(cacheWorkers);
    phases.secondary += millisecondsSince(start);

    // Composition: the sum the ray pipeline forms per pixel, or the background.
    start = Clock::now();
    parallel_.forEachTile(width, height, tileSize, [&](const TileRange& tile, int) {
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const std::size_t i = gbuffer.index(x, y);
                if (!gbuffer.hasSurface(i)) {
                    film.at(x, y) = integrator_.background(cameraRays.ray(x, y));
                    continue;
                }
                film.at(x, y) = needsSecondary_[static_cast<std::size_t>(gbuffer.objectId(i))]
                                    ? direct_[i] + secondary_[i]
                                    : direct_[i];
            }
    });
    phases.compose += millisecondsSince(start);
}

}  // namespace raycache
