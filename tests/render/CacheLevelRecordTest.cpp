// The tile kernel's per-pixel cache-level record (render/CacheLevelImage.h)
// against what it must agree with: the tracer's first hits (which pixels
// have a caching ray at all), the frame's own lookup counters (hitsByLevel,
// misses), the ray and hybrid pipelines against each other, and the image
// rendered without the record.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "core/Parallel.h"
#include "render/CacheLevelImage.h"
#include "render/CameraRays.h"
#include "render/FrameRenderer.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

constexpr std::size_t kNone = 0, kTraced = 1;  // CacheLevelImage::Counts indices; level k is at 2 + k

RenderSettings roomSettings(int cubeLevels, float errorBound) {
    RenderSettings s;
    s.width = s.height = 96;
    s.threads = 2;
    s.cache.techniqueOverride = CacheTechnique::Cct;
    s.cache.resolutionOverride = 64;
    s.cache.cubeLevels = cubeLevels;
    s.cache.levelErrorBound = errorBound;
    s.recordCacheLevels = true;
    return s;
}

int objectNamed(const Scene& scene, const std::string& name) {
    for (std::size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i].name == name) return static_cast<int>(i);
    ADD_FAILURE() << "no object " << name;
    return -1;
}

// In `room` the mirror ball is the only object that reflects or refracts,
// and a sphere's reflections never meet it again: a pixel asks the cache
// exactly once when its camera ray hits the ball, never otherwise. So the
// record's counts must equal the frame's lookup counters.
void expectCountsMatchTheCounters(const CacheLevelImage& levels, const FrameCacheStats& stats, int frame) {
    const CacheLevelImage::Counts counts = levels.counts();
    EXPECT_EQ(static_cast<std::uint64_t>(counts[kTraced]), stats.misses()) << "frame " << frame;
    for (int k = 0; k < kMaxCubeLevels; ++k)
        EXPECT_EQ(static_cast<std::uint64_t>(counts[2 + static_cast<std::size_t>(k)]), stats.hitsAtLevel(k))
            << "frame " << frame << ", level " << k;
    EXPECT_EQ(static_cast<std::uint64_t>(levels.values().size()) - static_cast<std::uint64_t>(counts[kNone]),
              stats.lookups())
        << "frame " << frame;
}

}  // namespace

TEST(CacheLevelRecord, FirstFrameTracesEveryMirrorPixelTheSecondAnswersThemAtTheFinestLevel) {
    const Scene scene = *makeBuiltinScene("room");
    const RenderSettings settings = roomSettings(1, 0.25f);
    const TraceScene tracer(scene);
    const Parallel parallel(settings.threads);
    RayCache cache(scene, settings.cache);
    const FrameRenderer renderer(scene, tracer, settings, parallel, &cache);

    // Which pixels see the mirror ball, from the tracer alone.
    const int ball = objectNamed(scene, "mirror-ball");
    const CameraRays rays(scene.camera, settings.width, settings.height);
    std::vector<bool> onBall;
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x) onBall.push_back(tracer.intersect(rays.ray(x, y)).objectId == ball);
    const auto ballPixels = static_cast<std::int64_t>(std::count(onBall.begin(), onBall.end(), true));
    ASSERT_GT(ballPixels, 100);

    Image film;
    CacheLevelImage levels;
    for (int frame = 0; frame < 2; ++frame) {
        const FrameStats stats = renderer.render(scene.camera, film, &levels);
        ASSERT_EQ(levels.width(), settings.width);
        ASSERT_EQ(levels.height(), settings.height);
        // Empty caches trace every lookup; the same camera again finds every
        // texel its rays filled.
        const std::int8_t expected = frame == 0 ? CacheLevelImage::kTraced : std::int8_t{0};
        for (int y = 0; y < settings.height; ++y)
            for (int x = 0; x < settings.width; ++x) {
                const bool ballPixel = onBall[static_cast<std::size_t>(y * settings.width + x)];
                ASSERT_EQ(levels.at(x, y), ballPixel ? expected : CacheLevelImage::kNoCachingRay)
                    << "frame " << frame << " pixel " << x << "," << y;
            }
        const CacheLevelImage::Counts counts = levels.counts();
        EXPECT_EQ(counts[kNone], static_cast<std::int64_t>(onBall.size()) - ballPixels);
        EXPECT_EQ(counts[frame == 0 ? kTraced : 2], ballPixels);
        expectCountsMatchTheCounters(levels, *stats.cache, frame);
    }
}

TEST(CacheLevelRecord, CoarseLevelsAnswerSomePixelsAndTheCountsEqualHitsByLevel) {
    // A moving camera and a loose error bound: the finest texels the new
    // rays address are often still empty, coarser ones already hold an answer.
    const auto scene = makeBuiltinScene("room");
    const RenderSettings settings = roomSettings(4, 1000.0f);
    const TraceScene tracer(*scene);
    const Parallel parallel(settings.threads);
    RayCache cache(*scene, settings.cache);
    const FrameRenderer renderer(*scene, tracer, settings, parallel, &cache);
    Image film;
    CacheLevelImage levels;
    std::int64_t coarse = 0, finest = 0;
    for (int frame = 0; frame < 4; ++frame) {
        const FrameStats stats = renderer.render(scene->cameraPath.cameraAt(scene->camera, frame), film, &levels);
        expectCountsMatchTheCounters(levels, *stats.cache, frame);
        const CacheLevelImage::Counts counts = levels.counts();
        finest += counts[2];
        for (std::size_t k = 3; k < counts.size(); ++k) coarse += counts[k];
    }
    std::printf("room 96², 4 levels of 64², bound 1000, frames 1-4: %lld pixels answered at level 0, %lld coarser\n",
                static_cast<long long>(finest), static_cast<long long>(coarse));
    EXPECT_GT(finest, 0);
    EXPECT_GT(coarse, 0);
}

TEST(CacheLevelRecord, TheRecordNeverChangesTheImageNorTheCachesAndIsMadeOnlyWhenAsked) {
    const auto scene = makeBuiltinScene("grid-8");  // mirrors that see each other: chains of lookups
    RenderSettings on;
    on.width = 80;
    on.height = 64;
    on.threads = 2;
    on.cache.techniqueOverride = CacheTechnique::Cct;
    on.cache.resolutionOverride = 64;
    on.cache.cubeLevels = 4;
    on.cache.levelErrorBound = 4.0f;
    on.recordCacheLevels = true;
    RenderSettings off = on;
    off.recordCacheLevels = false;

    const TraceScene tracer(*scene);
    const Parallel parallel(on.threads);
    RayCache cacheOn(*scene, on.cache), cacheOff(*scene, off.cache);
    const FrameRenderer withRecord(*scene, tracer, on, parallel, &cacheOn);
    const FrameRenderer without(*scene, tracer, off, parallel, &cacheOff);
    Image filmOn, filmOff;
    CacheLevelImage levelsOn, levelsOff;
    std::int64_t answered = 0;
    std::uint64_t lookups = 0, askingPixels = 0;
    for (int frame = 0; frame < 3; ++frame) {
        const Camera camera = scene->cameraPath.cameraAt(scene->camera, frame);
        const FrameStats a = withRecord.render(camera, filmOn, &levelsOn);
        const FrameStats b = without.render(camera, filmOff, &levelsOff);
        ASSERT_EQ(filmOn.pixels().size(), filmOff.pixels().size());
        EXPECT_EQ(std::memcmp(filmOn.pixels().data(), filmOff.pixels().data(), filmOn.pixels().size() * sizeof(Rgb)), 0)
            << "frame " << frame;
        EXPECT_EQ(a.cache->lookups(), b.cache->lookups());
        EXPECT_EQ(a.cache->hits(), b.cache->hits());
        for (int k = 0; k < kMaxCubeLevels; ++k) EXPECT_EQ(a.cache->hitsAtLevel(k), b.cache->hitsAtLevel(k));
        // Off, the buffer handed in is not touched.
        EXPECT_EQ(levelsOff.width(), 0);
        EXPECT_TRUE(levelsOff.values().empty());
        ASSERT_EQ(levelsOn.width(), on.width);
        const CacheLevelImage::Counts counts = levelsOn.counts();
        // Chains ask more than once per pixel: each pixel keeps one lookup, so
        // no level can show more pixels than it answered lookups.
        EXPECT_LE(static_cast<std::uint64_t>(counts[kTraced]), a.cache->misses());
        for (int k = 0; k < kMaxCubeLevels; ++k)
            EXPECT_LE(static_cast<std::uint64_t>(counts[2 + static_cast<std::size_t>(k)]), a.cache->hitsAtLevel(k));
        for (std::size_t k = 2; k < counts.size(); ++k) answered += counts[k];
        lookups += a.cache->lookups();
        askingPixels += levelsOn.values().size() - static_cast<std::uint64_t>(counts[kNone]);
    }
    EXPECT_GT(answered, 0);
    EXPECT_GT(lookups, askingPixels);  // some pixels did ask more than once
    for (std::size_t i = 0; i < scene->objects.size(); ++i) {
        const int id = static_cast<int>(i);
        if (!cacheOn.cachesObject(id)) continue;
        EXPECT_TRUE(std::equal(cacheOn.cube(id).texels().begin(), cacheOn.cube(id).texels().end(),
                               cacheOff.cube(id).texels().begin(), cacheOff.cube(id).texels().end()))
            << scene->objects[i].name;
        for (int k = 1; k < cacheOn.coarseLevels(id).levelCount(); ++k) {
            const auto& a = cacheOn.coarseLevels(id).level(k).texels();
            const auto& b = cacheOff.coarseLevels(id).level(k).texels();
            EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << scene->objects[i].name << " level " << k;
        }
    }
}

TEST(CacheLevelRecord, AGlassPixelKeepsItsWeightiestLookupNotItsFirst) {
    // A glass sphere facing the camera: a pixel at its centre asks the cache
    // first for its outer reflection (kr = 0.1, heading back to the camera,
    // +z) and then for the light leaving the back of the sphere (kt² = 0.81,
    // heading away, -z). Only the texels of directions with z < 0 are filled,
    // so the first lookup is traced and the second answered: the pixel must
    // show the answer.
    Scene scene;
    Material glass;
    glass.reflectivity = 0.1f;
    glass.transmissivity = 0.9f;
    glass.ior = 1.5f;
    glass.cache = {CacheTechnique::Cct, 64};
    scene.objects.push_back(SceneObject{"glass", Sphere{Vec3{}, 1.0f}, glass, Vec3{}});
    scene.environment = Environment::constant(Rgb{0.3f, 0.4f, 0.5f});
    scene.camera = Camera{{0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 40.0f};
    RenderSettings settings;
    settings.width = settings.height = 32;
    settings.threads = 2;
    settings.recordCacheLevels = true;

    const TraceScene tracer(scene);
    const Parallel parallel(settings.threads);
    RayCache cache(scene, settings.cache);
    std::vector<CacheWorker> workers = cache.makeWorkers(1);
    cache.beginFrame(workers);
    workers[0].beginBatch(0);
    for (int t = 0; t < static_cast<int>(cache.cube(0).texelCount()); ++t) {
        const Vec3 d = cache.prefillDirection(0, t);
        if (d.z < 0.0f) cache.store(0, Vec3{}, d, Rgb{1.0f, 0.0f, 0.0f}, 10.0f, workers[0]);
    }
    cache.endFrame(workers);

    const FrameRenderer renderer(scene, tracer, settings, parallel, &cache);
    Image film;
    CacheLevelImage levels;
    const FrameStats stats = renderer.render(scene.camera, film, &levels);
    EXPECT_GT(stats.cache->misses(), 0u);  // the outer reflections were asked for, and traced
    EXPECT_GT(stats.cache->hits(), 0u);
    for (int y = 15; y <= 16; ++y)
        for (int x = 15; x <= 16; ++x) EXPECT_EQ(levels.at(x, y), 0) << x << "," << y;
    EXPECT_EQ(levels.at(0, 0), CacheLevelImage::kNoCachingRay);  // a corner sees only the background
}

TEST(CacheLevelRecord, SessionsRecordOnlyWhenAskedAndTheHybridPipelineRecordsAsTheRayPipeline) {
    const Scene scene = *makeBuiltinScene("room");
    RenderSettings settings = roomSettings(4, 1000.0f);
    settings.recordCacheLevels = false;
    RenderSession ray(scene, settings);
    RenderSettings hybridSettings = settings;
    hybridSettings.pipeline = PipelineKind::Hybrid;
    hybridSettings.gbuffer = GBufferSource::Packets;
    RenderSession hybrid(scene, hybridSettings);

    Image film;
    ray.render(scene.camera, film);
    hybrid.render(scene.camera, film);
    EXPECT_EQ(ray.cacheLevels(), nullptr);
    EXPECT_EQ(hybrid.cacheLevels(), nullptr);

    // Turned on after a frame: the caches keep what that frame stored.
    ray.setRecordCacheLevels(true);
    hybrid.setRecordCacheLevels(true);
    for (int frame = 1; frame < 3; ++frame) {
        const Camera camera = scene.cameraPath.cameraAt(scene.camera, frame);
        const FrameStats stats = ray.render(camera, film);
        hybrid.render(camera, film);
        ASSERT_NE(ray.cacheLevels(), nullptr);
        ASSERT_NE(hybrid.cacheLevels(), nullptr);
        EXPECT_EQ(ray.cacheLevels()->values(), hybrid.cacheLevels()->values()) << "frame " << frame;
        EXPECT_GT(stats.cache->hits(), 0u) << "frame " << frame;
        expectCountsMatchTheCounters(*ray.cacheLevels(), *stats.cache, frame);
    }
    ray.setRecordCacheLevels(false);
    ray.render(scene.camera, film);
    EXPECT_EQ(ray.cacheLevels(), nullptr);

    RenderSettings renderCache = settings;
    renderCache.pipeline = PipelineKind::RenderCache;
    renderCache.recordCacheLevels = true;
    RenderSession session(scene, renderCache);
    session.render(scene.camera, film);
    EXPECT_EQ(session.cacheLevels(), nullptr);  // that pipeline makes no record
}
