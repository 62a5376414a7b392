// Animated scenes through a render session: every frame equals a render of
// the posed scene built from scratch (the uncached render of that pose is
// the truth), with caches on or off and for each pipeline.
#include <gtest/gtest.h>

#include <cstring>

#include "core/Errors.h"
#include "render/RenderSession.h"
#include "scene/BuiltinScenes.h"
#include "scene/ScenePose.h"

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

bool identical(const Image& a, const Image& b) {
    return a.width() == b.width() && a.height() == b.height() &&
           std::memcmp(a.pixels().data(), b.pixels().data(), sizeof(Rgb) * a.pixels().size()) == 0;
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
        EXPECT_TRUE(identical(film, truth)) << name << " frame " << frame;
        if (frame > 0) {
            EXPECT_GT(stats.sceneUpdate->objectsChanged + stats.sceneUpdate->lightsChanged, 0);
        }
    }
}

TEST(AnimatedSession, UncachedFramesEqualFreshRendersOfEachPose) {
    for (const char* name : {"room-moving", "orbit", "cloth", "light-sweep"})
        expectFramesMatchFreshRenders(name, CacheTechnique::None, PipelineKind::Ray);
}

// The caches forget what changed, so a cached frame of a moving scene shows
// no stale reflection: it equals the uncached render of its pose.
TEST(AnimatedSession, CachedFramesEqualUncachedRendersOfEachPose) {
    for (const char* name : {"room-moving", "orbit", "light-sweep"})
        expectFramesMatchFreshRenders(name, CacheTechnique::Cct, PipelineKind::Ray);
    expectFramesMatchFreshRenders("orbit", CacheTechnique::Cdct, PipelineKind::Ray);
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
    for (const ObjectAnimation& a : scene.animation.objects) {
        if (!session.cache().cachesObject(a.object)) continue;
        const Vec3 c = session.cache().cube(a.object).center();
        const Vec3 o = session.scene().objects[static_cast<std::size_t>(a.object)].origin;
        EXPECT_EQ(c, o);
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
