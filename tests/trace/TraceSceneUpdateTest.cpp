// The tracer moved by update() answers every ray as a tracer built afresh
// from the posed scene does: an external oracle for instances, refits and
// moving spheres.
#include <gtest/gtest.h>

#include "render/CameraRays.h"
#include "scene/BuiltinScenes.h"
#include "scene/ScenePose.h"
#include "core/Errors.h"
#include "trace/TraceScene.h"

namespace raycache {
namespace {

// The posed scene as a still scene: one flat hierarchy, nothing animated.
Scene stillCopy(const Scene& posed) {
    Scene still = posed;
    still.animation = SceneAnimation{};
    return still;
}

void expectSameAnswers(const Scene& posed, const TraceScene& moved, const std::string& what) {
    const TraceScene fresh(stillCopy(posed));
    const CameraRays rays(posed.camera, 96, 96);
    int hits = 0, mismatches = 0;
    std::vector<Ray> batch;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) batch.push_back(rays.ray(x, y));
    std::vector<TraceHit> a(batch.size()), b(batch.size());
    moved.intersectCoherent(batch, a);
    fresh.intersectCoherent(batch, b);
    std::vector<Ray> shadow;
    for (std::size_t i = 0; i < batch.size(); ++i) {
        if (a[i].objectId != b[i].objectId || a[i].primitiveId != b[i].primitiveId ||
            std::fabs(a[i].t - b[i].t) > 1e-4f * std::max(1.0f, b[i].t))
            ++mismatches;
        if (!b[i].hit()) continue;
        ++hits;
        const Vec3 p = batch[i].origin + batch[i].direction * b[i].t;
        const Vec3 toLight = posed.lights[0].position - p;
        shadow.push_back(Ray{p, normalize(toLight), 1e-3f, length(toLight)});
    }
    EXPECT_EQ(mismatches, 0) << what;
    EXPECT_GT(hits, 1000) << what;
    std::vector<unsigned char> oa(shadow.size()), ob(shadow.size());
    moved.occludedCoherent(shadow, oa);
    fresh.occludedCoherent(shadow, ob);
    EXPECT_EQ(oa, ob) << what << ": shadow answers";
    for (std::size_t i = 0; i < shadow.size(); i += 37) EXPECT_EQ(moved.occluded(shadow[i]), ob[i] != 0) << what;
}

TEST(TraceSceneUpdate, EveryAnimatedBuiltinMatchesAFreshBuildAlongItsAnimation) {
    for (const char* name : {"room-moving", "orbit", "cloth", "light-sweep"}) {
        const Scene scene = *makeBuiltinScene(name);
        Scene posed = scene;
        TraceScene tracer(posed);
        for (float time : {0.3f, 1.1f, 2.7f}) {
            const SceneChanges changes = poseScene(scene, time, posed);
            tracer.update(posed, changes.objects);
            expectSameAnswers(posed, tracer, std::string(name) + " at " + std::to_string(time) + " s");
        }
    }
}

TEST(TraceSceneUpdate, RigidMeshInstanceFollowsItsKeys) {
    // A box moved and turned by keys: an instance, whose hits name the box.
    Scene scene = *makeBuiltinScene("room");
    const int box = 3;  // object1 of the ring: a box
    ASSERT_TRUE(std::holds_alternative<MeshShape>(scene.objects[box].shape));
    TransformTrack track;
    track.keys = {TransformKey{0.0f, {}, {}, {1, 1, 1}},
                  TransformKey{1.0f, {-2, 0.5f, 1}, Quaternion::fromAxisAngle({0, 1, 0}, 60.0f), {1, 1.5f, 1}}};
    scene.animation.objects.push_back(ObjectAnimation{box, track, nullptr, scene.objects[box].shape, scene.objects[box].origin});
    Scene posed = scene;
    TraceScene tracer(posed);
    for (float time : {0.25f, 0.5f, 1.0f}) {
        const SceneChanges changes = poseScene(scene, time, posed);
        ASSERT_EQ(changes.objects, std::vector<int>{box});
        tracer.update(posed, changes.objects);
        expectSameAnswers(posed, tracer, "box at " + std::to_string(time) + " s");
    }
}

TEST(TraceSceneUpdate, RebuildingAStillSceneMatchesAFreshBuild) {
    // The bench's opponent "Embree rebuilt every frame": one still scene kept,
    // its objects set to each new pose and every hierarchy built again.
    for (const char* name : {"cloth", "orbit"}) {
        const Scene scene = *makeBuiltinScene(name);
        Scene posed = scene;
        TraceOptions low;
        low.stillSceneQuality = EmbreeBuildQuality::Low;
        TraceScene tracer(stillCopy(posed), low);
        for (float time : {0.7f, 2.2f}) {
            poseScene(scene, time, posed);
            tracer.rebuild(stillCopy(posed));
            expectSameAnswers(posed, tracer, std::string(name) + " rebuilt at " + std::to_string(time) + " s");
        }
    }
}

TEST(TraceSceneUpdate, RebuildingRefusesAnimatedTracersAndOtherTopologies) {
    const Scene cloth = *makeBuiltinScene("cloth");
    TraceScene animated(cloth);
    EXPECT_THROW(animated.rebuild(stillCopy(cloth)), RuntimeError) << "its objects move by update()";
    TraceScene still(stillCopy(cloth));
    Scene fewer = stillCopy(cloth);
    fewer.objects.pop_back();
    EXPECT_THROW(still.rebuild(fewer), RuntimeError);
    Scene otherMesh = stillCopy(cloth);
    for (SceneObject& object : otherMesh.objects)
        if (auto* mesh = std::get_if<MeshShape>(&object.shape)) {
            auto smaller = std::make_shared<TriangleMesh>(*mesh->mesh);
            smaller->positions.pop_back();
            mesh->mesh = smaller;
            break;
        }
    EXPECT_THROW(still.rebuild(otherMesh), RuntimeError);
}

TEST(TraceSceneUpdate, MovingAnObjectTheSceneDoesNotAnimateIsAnError) {
    const Scene scene = *makeBuiltinScene("room-moving");
    TraceScene tracer(scene);
    const std::vector<int> floor{0};
    EXPECT_THROW(tracer.update(scene, floor), RuntimeError);
}

}  // namespace
}  // namespace raycache

namespace raycache {
namespace {

// The `bowl` scene's objects: floor, bowl, ball in the bowl, torus, ball in
// the torus, box.
constexpr int kBowl = 1, kBallInBowl = 2, kTorus = 3, kBallInTorus = 4;
const Vec3 kBowlCentre{-1.2f, 1.55f, 0.0f};
// From the bowl's centre down its axis (tipped 40 degrees toward +z): through
// the ball that lies in it, to the bowl's inside wall.
const Vec3 kIntoBowl = normalize(Vec3{0.0f, -0.766f, -0.643f});

}  // namespace

TEST(TraceSceneOwnSurface, MeetsOnlyTheObjectItselfWhateverLiesInFront) {
    const Scene scene = *makeBuiltinScene("bowl");
    const TraceScene tracer(scene);
    tracer.prepareOwnSurfaceTests(std::vector<int>{kBowl});
    const Ray down{kBowlCentre, kIntoBowl};
    EXPECT_EQ(tracer.intersect(down).objectId, kBallInBowl) << "the ball lies in front of the wall";
    EXPECT_TRUE(tracer.meetsObject(kBowl, down));
    EXPECT_FALSE(tracer.meetsObject(kBowl, Ray{kBowlCentre, -kIntoBowl})) << "out through the bowl's opening";
    EXPECT_FALSE(tracer.meetsObject(kBowl, Ray{kBowlCentre, kIntoBowl, 0.0f, 0.5f})) << "stops short of the wall";
    // Spheres need no hierarchy of their own.
    const Vec3 ballTop{2.4f, 1.0001f, 0.6f};
    EXPECT_FALSE(tracer.meetsObject(kBallInTorus, Ray{ballTop, {0, 1, 0}}));
    EXPECT_TRUE(tracer.meetsObject(kBallInTorus, Ray{ballTop + Vec3{0, 2, 0}, {0, -1, 0}}));
    // A mesh whose hierarchy was not built is a caller's mistake, not a miss.
    EXPECT_THROW((void)tracer.meetsObject(kTorus, down), RuntimeError);
}

TEST(TraceSceneOwnSurface, FollowsARigidlyMovingMesh) {
    Scene scene = *makeBuiltinScene("bowl");
    TransformTrack track;
    track.keys = {TransformKey{0.0f, {}, {}, {1, 1, 1}}, TransformKey{1.0f, {20, 0, 0}, {}, {1, 1, 1}}};
    scene.animation.objects.push_back(
        ObjectAnimation{kBowl, track, nullptr, scene.objects[kBowl].shape, scene.objects[kBowl].origin});
    Scene posed = scene;
    TraceScene tracer(posed);
    tracer.prepareOwnSurfaceTests(std::vector<int>{kBowl});
    const Ray down{kBowlCentre, kIntoBowl};
    const Ray movedDown{kBowlCentre + Vec3{10, 0, 0}, kIntoBowl};
    EXPECT_TRUE(tracer.meetsObject(kBowl, down));
    EXPECT_FALSE(tracer.meetsObject(kBowl, movedDown));
    const SceneChanges changes = poseScene(scene, 0.5f, posed);  // halfway: 10 along x
    ASSERT_EQ(changes.objects, std::vector<int>{kBowl});
    tracer.update(posed, changes.objects);
    EXPECT_FALSE(tracer.meetsObject(kBowl, down));
    EXPECT_TRUE(tracer.meetsObject(kBowl, movedDown));
}

}  // namespace raycache
