// Animated scenes through a render session: every frame equals a render of
// the posed scene built from scratch (the uncached render of that pose is
// the truth), with caches on or off and for each pipeline.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

#include "ImageCompare.h"
#include "metrics/ImageMetrics.h"

#include "core/Errors.h"
#include "scene/BuiltinScenes.h"
#include "scene/ScenePose.h"
#include "session/RenderSession.h"

namespace raycache {
namespace {

RenderSettings smallSettings(CacheTechnique technique, PipelineKind pipeline = PipelineKind::Ray) {
    RenderSettings s;
    s.width = 80;
    s.height = 64;
    s.threads = 2;
    s.pipeline = pipeline;
    s.cache.techniqueOverride = technique;
    return s;
}

// The scene posed at `time`, with no animation left: what a fresh session sees.
Scene stillPoseAt(const Scene& scene, float time) {
    Scene posed = scene;
    poseScene(scene, time, posed);
    posed.animation = SceneAnimation{};
    return posed;
}

void expectFramesMatchFreshRenders(const std::string& name, CacheTechnique technique, PipelineKind pipeline) {
    const Scene scene = *makeBuiltinScene(name);
    const RenderSettings settings = smallSettings(technique, pipeline);
    RenderSession animated(scene, settings);
    Image film, truth;
    for (int frame = 0; frame < 4; ++frame) {
        const float time = static_cast<float>(frame) / scene.fps;
        animated.setTime(time);
        const FrameStats stats = animated.render(scene.camera, film);
        ASSERT_TRUE(stats.sceneUpdate.has_value());
        const Scene still = stillPoseAt(scene, time);
        RenderSession fresh(still, smallSettings(CacheTechnique::None, pipeline));
        fresh.render(still.camera, truth);
        EXPECT_TRUE(identicalImages(film, truth)) << name << " frame " << frame;
        if (frame > 0) {
            EXPECT_GT(stats.sceneUpdate->objectsChanged + stats.sceneUpdate->lightsChanged, 0);
        }
    }
}

TEST(AnimatedSession, UncachedFramesEqualFreshRendersOfEachPose) {
    for (const char* name : {"room-moving", "orbit", "cloth", "light-sweep"})
        expectFramesMatchFreshRenders(name, CacheTechnique::None, PipelineKind::Ray);
}

// CDCT cubes are dropped whole on any change (their searches read across
// blocks), so a CDCT frame of a moving scene is its pose's uncached render.
TEST(AnimatedSession, CdctFramesEqualUncachedRendersOfEachPose) {
    expectFramesMatchFreshRenders("orbit", CacheTechnique::Cdct, PipelineKind::Ray);
}

// CCT keeps the blocks no change can reach (tests/cache/InvalidationOracleTest:
// none stale). So its lookups keep hitting while things move, and a frame is
// as close to the uncached render of its pose as CCT gets on that pose
// standing still after as many frames.
TEST(AnimatedSession, CctKeepsAnsweringWhileTheSceneMoves) {
    for (const char* name : {"room-moving", "orbit", "light-sweep"}) {
        const Scene scene = *makeBuiltinScene(name);
        RenderSession animated(scene, smallSettings(CacheTechnique::Cct));
        Image film, truth, stillFilm;
        for (int frame = 0; frame < 5; ++frame) {
            const float time = static_cast<float>(frame) / scene.fps;
            animated.setTime(time);
            const FrameStats stats = animated.render(scene.camera, film);
            const Scene still = stillPoseAt(scene, time);
            RenderSession fresh(still, smallSettings(CacheTechnique::None));
            fresh.render(still.camera, truth);
            RenderSession stillCct(still, smallSettings(CacheTechnique::Cct));
            for (int k = 0; k <= frame; ++k) stillCct.render(still.camera, stillFilm);
            const double movingPsnr = psnr(film, truth), stillPsnr = psnr(stillFilm, truth);
            std::printf("[cct] %s frame %d: %llu of %llu lookups hit, PSNR %.2f dB (still %.2f dB)\n", name, frame,
                        static_cast<unsigned long long>(stats.cache->hits()),
                        static_cast<unsigned long long>(stats.cache->lookups()), movingPsnr, stillPsnr);
            if (frame > 0) {
                EXPECT_GT(stats.cache->hits(), 0u) << name << " frame " << frame;
            }
            EXPECT_GE(movingPsnr, stillPsnr - 1.0) << name << " frame " << frame;
        }
    }
}

TEST(AnimatedSession, HybridPipelineFollowsMovingMeshesAndSpheres) {
    expectFramesMatchFreshRenders("orbit", CacheTechnique::None, PipelineKind::Hybrid);
    expectFramesMatchFreshRenders("cloth", CacheTechnique::None, PipelineKind::Hybrid);
}

TEST(AnimatedSession, InvalidatedTexelsAreCountedAndCubesFollowTheirObjects) {
    const Scene scene = *makeBuiltinScene("orbit");
    RenderSession session(scene, smallSettings(CacheTechnique::Cct));
    Image film;
    session.setTime(0.0f);
    session.render(scene.camera, film);
    const SceneUpdateStats update = session.setTime(0.5f);
    EXPECT_EQ(update.objectsChanged, 4);
    EXPECT_GT(update.texelsInvalidated, 0);
    // The inspector's view of the change: exactly the dropped texels, each now invalid.
    std::int64_t marked = 0;
    for (int object = 0; object < static_cast<int>(scene.objects.size()); ++object) {
        if (!session.cache().cachesObject(object)) continue;
        const auto bits = session.cache().droppedByLastChange(object);
        for (std::size_t t = 0; t < session.cache().cube(object).texelCount(); ++t)
            if ((bits[t >> 6] >> (t & 63)) & 1u) {
                ++marked;
                EXPECT_FALSE(session.cache().cube(object).isValid(static_cast<int>(t)));
            }
    }
    EXPECT_EQ(marked, update.texelsInvalidated);
    for (const ObjectAnimation& a : scene.animation.objects) {
        if (!session.cache().cachesObject(a.object)) continue;
        const Vec3 c = session.cache().cube(a.object).center();
        const Vec3 o = session.scene().objects[static_cast<std::size_t>(a.object)].origin;
        EXPECT_EQ(c, o);
    }
}

// Multi-resolution cubes (cache/CoarseLevels.h): a coarse texel may hold the
// store of any finest texel under it, so every coarse texel over a dropped
// finest texel must go too. The camera orbits so that coarse texels answer.
TEST(AnimatedSession, CoarseLevelsOverDroppedTexelsAreDroppedToo) {
    for (const char* name : {"room-moving", "light-sweep"}) {
        const Scene scene = *makeBuiltinScene(name);
        RenderSettings settings = smallSettings(CacheTechnique::Cct);
        settings.cache.cubeLevels = 4;
        settings.cache.levelErrorBound = 1.0f;
        settings.cache.resolutionOverride = 64;
        // Every store made, so that every change has texels to drop.
        settings.cache.skipStoresReachingChanges = false;
        RenderSession session(scene, settings);
        CameraPath orbit;
        orbit.kind = CameraPathKind::Orbit;
        orbit.center = scene.camera.lookAt;
        orbit.degreesPerFrame = 2.0f;
        Image film;
        std::uint64_t coarseHits = 0;
        std::int64_t checked = 0;
        for (int frame = 0; frame < 6; ++frame) {
            const SceneUpdateStats update = session.setTime(static_cast<float>(frame) / scene.fps);
            if (frame > 0) {
                EXPECT_GT(update.texelsInvalidated, 0) << name << " frame " << frame;
            }
            for (int object = 0; object < static_cast<int>(scene.objects.size()); ++object) {
                if (!session.cache().cachesObject(object)) continue;
                const auto bits = session.cache().droppedByLastChange(object);
                const CoarseLevels& levels = session.cache().coarseLevels(object);
                ASSERT_EQ(levels.levelCount(), 4);
                for (std::size_t t = 0; t < bits.size() * 64 && t < session.cache().cube(object).texelCount(); ++t) {
                    if (!((bits[t >> 6] >> (t & 63)) & 1u)) continue;
                    for (int k = 1; k < levels.levelCount(); ++k) {
                        ++checked;
                        EXPECT_FALSE(levels.level(k).isValid(levels.texelOver(static_cast<int>(t), k)))
                            << name << " frame " << frame << " texel " << t << " level " << k;
                    }
                }
            }
            const FrameStats stats = session.render(orbit.cameraAt(scene.camera, frame), film);
            for (int k = 1; k < stats.cache->levels(); ++k) coarseHits += stats.cache->hitsAtLevel(k);
        }
        EXPECT_GT(checked, 0) << name;
        EXPECT_GT(coarseHits, 0u) << name;
    }
}

// RayCacheSettings::skipStoresReachingChanges: a light that moves every
// frame. Without the skip, every change drops what the frame before stored
// under that light; with it, nothing shaded is stored while the light moves,
// so later changes find nothing to drop, and the frames stay as close to
// the uncached render of their pose.
TEST(AnimatedSession, StoresReachingAMovingLightAreSkippedWhileItMoves) {
    const Scene scene = *makeBuiltinScene("light-sweep");
    for (const bool skip : {false, true}) {
        RenderSettings settings = smallSettings(CacheTechnique::Cct);
        settings.cache.skipStoresReachingChanges = skip;
        RenderSession session(scene, settings);
        Image film, truth;
        std::int64_t droppedAfterFirstChange = 0;
        for (int frame = 0; frame < 4; ++frame) {
            const float time = static_cast<float>(frame) / scene.fps;
            const SceneUpdateStats update = session.setTime(time);
            if (frame >= 2) droppedAfterFirstChange += update.texelsInvalidated;
            const FrameStats stats = session.render(scene.camera, film);
            // Frame 0 follows no change: every store is made.
            if (frame == 0 || !skip) {
                EXPECT_EQ(stats.cache->skippedStores(), 0u) << "frame " << frame;
                EXPECT_GT(stats.cache->stores(), 0u) << "frame " << frame;
            } else {
                EXPECT_GT(stats.cache->skippedStores(), 0u) << "frame " << frame;
            }
            const Scene still = stillPoseAt(scene, time);
            RenderSession fresh(still, smallSettings(CacheTechnique::None));
            fresh.render(still.camera, truth);
            EXPECT_GE(psnr(film, truth), 40.0) << "skip " << skip << " frame " << frame;
        }
        if (skip)
            EXPECT_EQ(droppedAfterFirstChange, 0);
        else
            EXPECT_GT(droppedAfterFirstChange, 0);
    }
}

// Once the scene stops changing, stores are made again.
TEST(AnimatedSession, StoresResumeWhenTheSceneStopsChanging) {
    const Scene scene = *makeBuiltinScene("orbit");
    RenderSession session(scene, smallSettings(CacheTechnique::Cct));
    Image film;
    session.setTime(0.0f);
    session.render(scene.camera, film);
    session.setTime(1.0f / scene.fps);
    const FrameStats moving = session.render(scene.camera, film);
    EXPECT_GT(moving.cache->skippedStores(), 0u);
    session.setTime(1.0f / scene.fps);  // the same pose: no change
    const FrameStats still = session.render(scene.camera, film);
    EXPECT_EQ(still.cache->skippedStores(), 0u);
    EXPECT_GT(still.cache->stores(), 0u);
}

// Improved CDCT cubes are emptied whole by any change, so while the scene
// moves they are not pre-filled (a whole cube traced per frame for nothing);
// the frame after the scene stops fills them.
TEST(AnimatedSession, CdctCubesWaitForTheSceneToStopBeforeTheirPrefill) {
    const Scene scene = *makeBuiltinScene("orbit");
    for (const bool skip : {false, true}) {
        RenderSettings settings = smallSettings(CacheTechnique::Cdct);
        settings.cache.resolutionOverride = 16;
        settings.cache.skipStoresReachingChanges = skip;
        RenderSession session(scene, settings);
        Image film;
        std::uint64_t prefilledWhileMoving = 0;
        for (int frame = 0; frame < 4; ++frame) {
            session.setTime(static_cast<float>(frame) / scene.fps);
            const FrameStats stats = session.render(scene.camera, film);
            if (frame > 0) prefilledWhileMoving += stats.cache->prefilledTexels();
        }
        session.setTime(3.0f / scene.fps);  // the same pose: the scene stopped
        const FrameStats stopped = session.render(scene.camera, film);
        if (skip) {
            EXPECT_EQ(prefilledWhileMoving, 0u);
            EXPECT_GT(stopped.cache->prefilledTexels(), 0u);
        } else {
            // Every moving frame filled the cubes again; the last fill stands.
            EXPECT_GT(prefilledWhileMoving, 0u);
            EXPECT_EQ(stopped.cache->prefilledTexels(), 0u);
        }
    }
}

TEST(AnimatedSession, StillSceneIgnoresTime) {
    const Scene scene = *makeBuiltinScene("grid-4");
    RenderSession session(scene, smallSettings(CacheTechnique::Cct));
    const SceneUpdateStats update = session.setTime(3.0f);
    EXPECT_EQ(update.objectsChanged, 0);
    Image film;
    EXPECT_FALSE(session.render(scene.camera, film).sceneUpdate.has_value());
}

TEST(AnimatedSession, SessionSharingItsTracerCannotAnimate) {
    const Scene scene = *makeBuiltinScene("orbit");
    const TraceScene tracer(scene);
    const Parallel parallel(1);
    RenderSession session(scene, smallSettings(CacheTechnique::None), tracer, parallel);
    EXPECT_THROW(session.setTime(1.0f), RuntimeError);
}

}  // namespace
}  // namespace raycache
