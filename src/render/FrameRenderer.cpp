#include "render/FrameRenderer.h"

#include <vector>

#include "render/CachePrefill.h"
#include "render/CameraRays.h"

namespace raycache {

namespace {

// Per-worker buffers for one tile, allocated once per frame rather than per
// tile or per ray.
struct TileScratch {
    std::vector<Ray> rays;                   // primary rays
    std::vector<TraceHit> hits;              // their nearest hits
    std::vector<SurfacePoint> points;        // surface at each hit
    std::vector<int> firstQuery;             // pixel i's queries: [firstQuery[i], firstQuery[i+1])
    std::vector<ShadowQuery> queries;        // shadow queries of the whole tile
    std::vector<Ray> shadowRays;             // the same rays, packed for the tracer
    std::vector<unsigned char> occluded;     // tracer's answers
    std::vector<unsigned char> visible;      // 1 - occluded, as directLight wants it
    RayCounts counts;

    TileScratch(std::size_t pixels, std::size_t lights)
        : rays(pixels), hits(pixels), points(pixels), firstQuery(pixels + 1), queries(pixels * lights),
          shadowRays(pixels * lights), occluded(pixels * lights), visible(pixels * lights) {}
};

}  // namespace

FrameRenderer::FrameRenderer(const Scene& scene, const TraceScene& tracer, const RenderSettings& settings,
                             const Parallel& parallel, RayCache* cache)
    : scene_(scene), tracer_(tracer), settings_(settings), parallel_(parallel),
      cache_(cache && !cache->empty() ? cache : nullptr), integrator_(scene, tracer, settings, cache_) {}

FrameStats FrameRenderer::render(const Camera& camera, Image& film) const {
    if (film.width() != settings_.width || film.height() != settings_.height)
        film = Image(settings_.width, settings_.height);
    const CameraRays cameraRays(camera, settings_.width, settings_.height);

    const auto tilePixels = static_cast<std::size_t>(settings_.tileSize) * static_cast<std::size_t>(settings_.tileSize);
    std::vector<TileScratch> scratch(static_cast<std::size_t>(parallel_.threadCount()),
                                     TileScratch(tilePixels, scene_.lights.size()));
    std::vector<CacheWorker> cacheWorkers;
    if (cache_) {
        cacheWorkers = cache_->makeWorkers(parallel_.threadCount());
        cache_->beginFrame(cacheWorkers);
    }

    parallel_.forEachTile(settings_.width, settings_.height, settings_.tileSize, [&](const TileRange& tile, int worker) {
        TileScratch& s = scratch[static_cast<std::size_t>(worker)];
        CacheWorker* cacheWorker = cache_ ? &cacheWorkers[static_cast<std::size_t>(worker)] : nullptr;
        PathContext path{s.counts, cacheWorker};
        const int tileWidth = tile.x1 - tile.x0;
        std::size_t n = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) s.rays[n++] = cameraRays.ray(x, y);
        const std::span<const Ray> primary(s.rays.data(), n);
        tracer_.intersectCoherent(primary, std::span(s.hits.data(), n));
        s.counts.primary += n;

        // Shadow rays of all primary hits in the tile, traced together: they
        // start close to each other and head for the same lights.
        std::size_t queryCount = 0;
        for (std::size_t i = 0; i < n; ++i) {
            s.firstQuery[i] = static_cast<int>(queryCount);
            if (!s.hits[i].hit()) continue;
            const SceneObject& object = scene_.objects[static_cast<std::size_t>(s.hits[i].objectId)];
            s.points[i] = surfacePointAt(object, s.rays[i], s.hits[i], object.material.diffuseTexture.has_value());
            queryCount += static_cast<std::size_t>(integrator_.shadowQueries(s.points[i], s.queries.data() + queryCount));
        }
        s.firstQuery[n] = static_cast<int>(queryCount);
        for (std::size_t q = 0; q < queryCount; ++q) s.shadowRays[q] = s.queries[q].ray;
        tracer_.occludedCoherent(std::span(s.shadowRays.data(), queryCount), std::span(s.occluded.data(), queryCount));
        for (std::size_t q = 0; q < queryCount; ++q) s.visible[q] = s.occluded[q] ? 0 : 1;
        s.counts.shadow += queryCount;

        for (std::size_t i = 0; i < n; ++i) {
            const int x = tile.x0 + static_cast<int>(i) % tileWidth;
            const int y = tile.y0 + static_cast<int>(i) / tileWidth;
            if (!s.hits[i].hit()) {
                film.at(x, y) = integrator_.background(s.rays[i]);
                continue;
            }
            const int objectId = s.hits[i].objectId;
            const Material& material = scene_.objects[static_cast<std::size_t>(objectId)].material;
            if (cacheWorker)
                cacheWorker->beginPixel(static_cast<std::uint32_t>(y) * static_cast<std::uint32_t>(settings_.width) +
                                        static_cast<std::uint32_t>(x));
            const auto first = static_cast<std::size_t>(s.firstQuery[i]);
            const auto count = static_cast<std::size_t>(s.firstQuery[i + 1]) - first;
            film.at(x, y) = integrator_.directLight(material, s.points[i], -s.rays[i].direction,
                                                    std::span(s.queries.data() + first, count),
                                                    std::span(s.visible.data() + first, count)) +
                            integrator_.secondaryLight(s.rays[i], s.points[i], objectId, 1, 1.0f, path);
        }
    });

    FrameStats stats;
    for (const TileScratch& s : scratch) stats.rays += s.counts;
    if (cache_) {
        stats.rays += prefillCaches(*cache_, cacheWorkers, integrator_, parallel_);
        stats.cache = cache_->endFrame(cacheWorkers);
    }
    return stats;
}

}  // namespace raycache
