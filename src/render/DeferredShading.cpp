#include "render/DeferredShading.h"

#include <chrono>

#include "render/CachePrefill.h"
#include "render/CameraRays.h"

namespace raycache {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Per-worker buffers for one tile, allocated once per frame.
struct TileScratch {
    std::vector<std::size_t> pixel;       // G-buffer index of each surface pixel in the tile, in order
    std::vector<Ray> ray;                 // its camera ray
    std::vector<SurfacePoint> points;     // its surface
    std::vector<Rgb> direct;              // its color: direct light, then plus secondary light
    std::vector<int> firstQuery;          // surface pixel k's queries: [firstQuery[k], firstQuery[k+1])
    std::vector<ShadowQuery> queries;
    std::vector<Ray> shadowRays;
    std::vector<unsigned char> occluded;
    std::vector<unsigned char> visible;
    RayCounts counts;
    Clock::duration shadows{}, secondary{}, compose{};  // time this worker spent in each phase

    TileScratch(std::size_t pixels, std::size_t lights)
        : pixel(pixels), ray(pixels), points(pixels), direct(pixels), firstQuery(pixels + 1),
          queries(pixels * lights), shadowRays(pixels * lights), occluded(pixels * lights), visible(pixels * lights) {}
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
    const CameraRays cameraRays(camera, width, height);
    const int tileSize = settings_.tileSize;
    const auto tilePixels = static_cast<std::size_t>(tileSize) * static_cast<std::size_t>(tileSize);
    const auto workers = static_cast<std::size_t>(parallel_.threadCount());
    PhaseTimes& phases = stats.phases.emplace(stats.phases.value_or(PhaseTimes{}));

    const auto frameStart = Clock::now();
    std::vector<CacheWorker> cacheWorkers;
    if (cache_) {
        cacheWorkers = cache_->makeWorkers(parallel_.threadCount());
        cache_->beginFrame(cacheWorkers);
    }
    // One pass over the tiles does the three phases in turn, so each tile's
    // surfaces are rebuilt once and stay in cache; every worker adds up the
    // time it spends in each phase, and the pass's wall time is split in
    // those proportions.
    std::vector<TileScratch> scratch(workers, TileScratch(tilePixels, scene_.lights.size()));
    parallel_.forEachTile(width, height, tileSize, [&](const TileRange& tile, int worker) {
        TileScratch& s = scratch[static_cast<std::size_t>(worker)];
        CacheWorker* cacheWorker = cache_ ? &cacheWorkers[static_cast<std::size_t>(worker)] : nullptr;
        PathContext path{s.counts, cacheWorker};
        const auto t0 = Clock::now();

        // Shadows: the rays of every surface pixel in the tile traced together
        // as packets (they start close to each other and head for the same lights).
        std::size_t n = 0, queryCount = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const std::size_t i = gbuffer.index(x, y);
                if (!gbuffer.hasSurface(i)) continue;
                s.pixel[n] = i;
                s.ray[n] = cameraRays.ray(x, y);
                s.points[n] = surfacePointFromGBuffer(scene_, gbuffer, i, s.ray[n].direction);
                s.firstQuery[n] = static_cast<int>(queryCount);
                queryCount +=
                    static_cast<std::size_t>(integrator_.shadowQueries(s.points[n], s.queries.data() + queryCount));
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
            s.direct[k] = integrator_.directLight(material, gbuffer.albedoAt(i), s.points[k], -s.ray[k].direction,
                                                  std::span(s.queries.data() + first, count),
                                                  std::span(s.visible.data() + first, count));
        }
        const auto t1 = Clock::now();

        // Secondary: only pixels whose material reflects or refracts, each
        // announced to its cache worker first so cache stores stay ordered by pixel.
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t i = s.pixel[k];
            const int objectId = gbuffer.objectId(i);
            if (!needsSecondary_[static_cast<std::size_t>(objectId)]) continue;
            if (cacheWorker) cacheWorker->beginPixel(static_cast<std::uint32_t>(i));
            // The sum the ray pipeline forms per pixel.
            s.direct[k] += integrator_.secondaryLight(s.ray[k], s.points[k], objectId, 1, 1.0f, path);
        }
        const auto t2 = Clock::now();

        // Composition: the shaded surfaces, the background elsewhere.
        std::size_t k = 0;
        for (int y = tile.y0; y < tile.y1; ++y)
            for (int x = tile.x0; x < tile.x1; ++x) {
                const std::size_t i = gbuffer.index(x, y);
                film.at(x, y) = k < n && s.pixel[k] == i ? s.direct[k++] : integrator_.background(cameraRays.ray(x, y));
            }
        const auto t3 = Clock::now();
        s.shadows += t1 - t0;
        s.secondary += t2 - t1;
        s.compose += t3 - t2;
    });
    Clock::duration shadows{}, secondary{}, compose{};
    for (const TileScratch& s : scratch) {
        stats.rays += s.counts;
        shadows += s.shadows;
        secondary += s.secondary;
        compose += s.compose;
    }
    const double passMs = millisecondsSince(frameStart);
    const auto mergeStart = Clock::now();
    if (cache_) {
        stats.rays += prefillCaches(*cache_, cacheWorkers, integrator_, parallel_);
        stats.cache = cache_->endFrame(cacheWorkers);
    }
    const double mergeMs = millisecondsSince(mergeStart);
    const double busy = std::chrono::duration<double>(shadows + secondary + compose).count();
    const auto share = [&](Clock::duration d) {
        return busy > 0.0 ? passMs * std::chrono::duration<double>(d).count() / busy : 0.0;
    };
    phases.shadows += share(shadows);
    phases.secondary += share(secondary) + mergeMs;  // the cache merge (and pre-fill) belongs to the secondary rays
    phases.compose += share(compose);
}

}  // namespace raycache
