// RenderSession (tracer + caches + threads + pipeline in one object) and
// CacheFrame (one frame of the caches, ended however the frame ends).
#include <gtest/gtest.h>

#include <cstring>

#include "ImageCompare.h"
#include "core/Parallel.h"
#include "render/CacheFrame.h"
#include "render/CameraRays.h"
#include "render/FrameRenderer.h"
#include "render/TileKernel.h"
#include "scene/BuiltinScenes.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

RenderSettings smallSessionSettings(CacheTechnique technique) {
    RenderSettings s;
    s.width = s.height = 48;
    s.threads = 2;
    s.cache.techniqueOverride = technique;
    s.cache.resolutionOverride = 32;
    return s;
}

}  // namespace

TEST(RenderSession, RendersWhatTheHandAssembledPartsRender) {
    const auto scene = makeBuiltinScene("grid-8");
    ASSERT_TRUE(scene.has_value());
    for (CacheTechnique technique : {CacheTechnique::None, CacheTechnique::Cct}) {
        const RenderSettings settings = smallSessionSettings(technique);
        RenderSession session(*scene, settings);
        const TraceScene tracer(*scene);
        const Parallel parallel(settings.threads);
        RayCache cache(*scene, settings.cache);
        const FrameRenderer renderer(*scene, tracer, settings, parallel, &cache);
        for (int frame = 0; frame < 3; ++frame) {
            const Camera camera = scene->cameraPath.cameraAt(scene->camera, frame);
            Image a, b;
            const FrameStats sa = session.render(camera, a);
            const FrameStats sb = renderer.render(camera, b);
            EXPECT_TRUE(identicalImages(a, b)) << cacheTechniqueName(technique) << " frame " << frame;
            EXPECT_EQ(sa.rays.total(), sb.rays.total());
            EXPECT_EQ(sa.cache.has_value(), technique != CacheTechnique::None);
        }
        EXPECT_EQ(session.description(), "pipeline: ray (primary rays as packets)");
    }
}

TEST(RenderSession, ResizeKeepsTheCaches) {
    const auto scene = makeBuiltinScene("grid-1");
    ASSERT_TRUE(scene.has_value());
    RenderSession session(*scene, smallSessionSettings(CacheTechnique::Cct));
    Image film;
    session.render(scene->camera, film);
    int mirror = 0;
    while (!session.cache().cachesObject(mirror)) ++mirror;
    const std::size_t valid = session.cache().cube(mirror).validCount();
    ASSERT_GT(valid, 0u);
    session.resize(24, 24);
    EXPECT_EQ(session.cache().cube(mirror).validCount(), valid);
    session.render(scene->camera, film);
    EXPECT_EQ(film.width(), 24);
    session.resize(48, 48);
    const FrameStats stats = session.render(scene->camera, film);
    EXPECT_EQ(film.width(), 48);
    ASSERT_TRUE(stats.cache.has_value());
    EXPECT_GT(stats.cache->lookups(), 0u);
    EXPECT_EQ(stats.cache->hits(), stats.cache->lookups())
        << "the same full-size view reads everything the first frame stored";
}

TEST(CacheFrame, AFrameLeftUnfinishedStillAppliesItsStoresAndLeavesTheCacheReady) {
    const auto scene = makeBuiltinScene("grid-1");
    ASSERT_TRUE(scene.has_value());
    RayCacheSettings settings;
    settings.techniqueOverride = CacheTechnique::Cct;
    settings.resolutionOverride = 16;
    RayCache cache(*scene, settings);
    int mirror = 0;
    while (!cache.cachesObject(mirror)) ++mirror;
    const Vec3 origin = scene->objects[static_cast<std::size_t>(mirror)].origin;
    const Vec3 d = normalize(Vec3{0.3f, 0.2f, -1.0f});
    {
        CacheFrame frame(&cache, 2);
        ASSERT_NE(frame.worker(1), nullptr);
        frame.worker(1)->beginBatch(0);
        cache.store(mirror, origin, d, Rgb{0.25f}, 1.0f, *frame.worker(1));
        // Leaves scope unfinished, as when a frame throws.
    }
    EXPECT_EQ(cache.cube(mirror).validCount(), 1u);
    CacheFrame next(&cache, 2);
    EXPECT_TRUE(cache.lookup(mirror, origin, d, *next.worker(0)).has_value());
    const TraceScene tracer(*scene);
    const TileKernel kernel(*scene, tracer, RenderSettings{}, &cache);
    RayCounts rays;
    const auto stats = next.finish(kernel, Parallel(1), rays);
    ASSERT_TRUE(stats.has_value());
    EXPECT_EQ(stats->hits(), 1u);
    EXPECT_EQ(stats->stores(), 0u);

    CacheFrame inactive(nullptr, 2);
    EXPECT_EQ(inactive.worker(0), nullptr);
    EXPECT_FALSE(inactive.finish(kernel, Parallel(1), rays).has_value());
}

// The stage timer's hit count (the unit of `--stage-times`' ns per hit)
// against the tracer's own answer: with one ray per path, the hits shaded
// are the camera rays that hit something.
TEST(RenderSession, StageTimesCountTheCameraRaysThatHit) {
    const auto scene = makeBuiltinScene("grid-8");
    ASSERT_TRUE(scene.has_value());
    RenderSettings settings = smallSessionSettings(CacheTechnique::None);
    settings.maxDepth = 1;
    settings.stageTimes = true;
    RenderSession session(*scene, settings);
    Image film;
    const FrameStats stats = session.render(scene->camera, film);
    ASSERT_TRUE(stats.stages.has_value());
    const TraceScene tracer(*scene);
    const CameraRays rays(scene->camera, settings.width, settings.height);
    std::uint64_t hits = 0;
    for (int y = 0; y < settings.height; ++y)
        for (int x = 0; x < settings.width; ++x) hits += tracer.intersect(rays.ray(x, y)).hit() ? 1 : 0;
    EXPECT_GT(hits, 0u);
    EXPECT_LT(hits, static_cast<std::uint64_t>(settings.width * settings.height));  // some pixels see the sky
    EXPECT_EQ(stats.stages->hitsShaded, hits);
    // With mirrors reflecting (the default depth), later bounces' hits count too.
    settings.maxDepth = 5;
    RenderSession deeper(*scene, settings);
    EXPECT_GT(deeper.render(scene->camera, film).stages->hitsShaded, hits);
}
