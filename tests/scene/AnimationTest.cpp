// Keyframe interpolation against values worked out by hand, and posing a
// scene: what changes, what stays untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/Animation.h"
#include "scene/BuiltinScenes.h"
#include "scene/ClothDrape.h"
#include "scene/ScenePose.h"

namespace raycache {
namespace {

void expectNear(const Vec3& a, const Vec3& b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TransformTrack twoKeys(Interpolation interpolation, Wrap wrap) {
    TransformTrack t;
    t.keys = {TransformKey{1.0f, {0, 0, 0}, {}, {1, 1, 1}},
              TransformKey{3.0f, {4, 0, 0}, Quaternion::fromAxisAngle({0, 1, 0}, 90.0f), {3, 3, 3}}};
    t.interpolation = interpolation;
    t.wrap = wrap;
    return t;
}

TEST(Animation, LinearKeysMoveAtAConstantRate) {
    const TransformTrack t = twoKeys(Interpolation::Linear, Wrap::Clamp);
    // A quarter of the way: translate 1, scale 1.5, a 22.5° turn about y.
    const Transform m = t.at(1.5f);
    expectNear(m.translation(), {1, 0, 0});
    const float a = 22.5f * std::numbers::pi_v<float> / 180.0f;
    expectNear(m.applyToVector({1, 0, 0}), Vec3{std::cos(a), 0, -std::sin(a)} * 1.5f);
}

TEST(Animation, SmoothKeysEaseInAndOutWithoutOvershoot) {
    const TransformTrack t = twoKeys(Interpolation::Smooth, Wrap::Clamp);
    // smoothstep(0.25) = 0.15625; the midpoint stays the midpoint.
    EXPECT_NEAR(t.at(1.5f).translation().x, 4.0f * 0.15625f, 1e-5f);
    EXPECT_NEAR(t.at(2.0f).translation().x, 2.0f, 1e-5f);
    for (float time = 1.0f; time <= 3.0f; time += 0.05f) {
        const float x = t.at(time).translation().x;
        EXPECT_GE(x, 0.0f);
        EXPECT_LE(x, 4.0f);
    }
}

TEST(Animation, ClampHoldsTheEndKeysAndLoopStartsAgain) {
    const TransformTrack clamp = twoKeys(Interpolation::Linear, Wrap::Clamp);
    EXPECT_EQ(clamp.at(-5.0f).translation().x, 0.0f);
    EXPECT_EQ(clamp.at(10.0f).translation().x, 4.0f);
    const TransformTrack loop = twoKeys(Interpolation::Linear, Wrap::Loop);
    // The period is 2 s (from the first key's time to the last's).
    EXPECT_NEAR(loop.at(3.5f).translation().x, 1.0f, 1e-5f);
    EXPECT_NEAR(loop.at(0.5f).translation().x, 3.0f, 1e-5f);  // before the first key: wrapped too
}

TEST(Animation, SlerpTurnsAtAConstantAngularRate) {
    const Quaternion a{}, b = Quaternion::fromAxisAngle({0, 0, 1}, 120.0f);
    for (float s : {0.0f, 0.25f, 0.5f, 1.0f}) {
        const Vec3 x = slerp(a, b, s).toTransform().applyToVector({1, 0, 0});
        const float angle = std::atan2(x.y, x.x) * 180.0f / std::numbers::pi_v<float>;
        EXPECT_NEAR(angle, 120.0f * s, 1e-3f);
    }
}

TEST(Animation, LightTrackSetsPositionDirectionAndIntensity) {
    Light base;
    base.type = LightType::Spot;
    base.coneAngleDeg = 20.0f;
    LightTrack track;
    track.keys = {LightKey{0.0f, {0, 10, 0}, {0, -1, 0}, Rgb{1.0f}}, LightKey{2.0f, {4, 10, 0}, {1, 0, 0}, Rgb{0.0f}}};
    track.wrap = Wrap::Clamp;
    const Light l = track.at(base, 1.0f);
    expectNear(l.position, {2, 10, 0});
    expectNear(l.direction, normalize(Vec3{0.5f, -0.5f, 0}));
    EXPECT_NEAR(l.intensity.r, 0.5f, 1e-6f);
    EXPECT_EQ(l.coneAngleDeg, 20.0f);  // not animated: the light's own
}

TEST(Animation, MeshSequenceBlendsFramesAndLoopsBackToTheFirst) {
    const MeshSequence sequence({{Vec3{0, 0, 0}}, {Vec3{2, 0, 0}}}, 10.0f, Wrap::Loop);
    Vec3 p;
    sequence.positionsAt(0.05f, std::span(&p, 1));  // halfway from frame 0 to 1
    expectNear(p, {1, 0, 0});
    sequence.positionsAt(0.15f, std::span(&p, 1));  // halfway from frame 1 back to 0
    expectNear(p, {1, 0, 0});
    sequence.positionsAt(0.2f, std::span(&p, 1));
    expectNear(p, {0, 0, 0});
}

TEST(ClothDrape, DrapedSheetLiesOnTheSphereOrBelowItsEquatorNeverInside) {
    const ClothDrapeShape shape{.cells = 40};
    const ClothDrape drape(shape);
    std::vector<Vec3> at(drape.vertexCount());
    drape.positionsAt(0.0f, at);
    for (const Vec3& p : at) EXPECT_EQ(p.y, shape.height);  // flat at time 0
    drape.positionsAt(0.5f * shape.period, at);             // fully draped
    for (const Vec3& p : at) {
        EXPECT_GE(length(p - shape.sphereCenter), shape.sphereRadius);
        EXPECT_GE(p.y, shape.floorY);
    }
    // The centre of the sheet rests on top of the sphere.
    const std::size_t middle = at.size() / 2;
    EXPECT_NEAR(at[middle].y, shape.sphereCenter.y + shape.sphereRadius, 0.05f);
}

TEST(ScenePose, ListsExactlyWhatMovedAndLeavesStillObjectsAlone) {
    const Scene scene = *makeBuiltinScene("room-moving");
    Scene posed = scene;
    const auto floorMesh = std::get<MeshShape>(posed.objects[0].shape).mesh;
    const SceneChanges changes = poseScene(scene, 0.5f, posed);
    ASSERT_EQ(changes.objects.size(), 1u);
    const int ball = changes.objects[0];
    EXPECT_EQ(posed.objects[static_cast<std::size_t>(ball)].name, "bouncing-ball");
    EXPECT_TRUE(changes.lights.empty());
    EXPECT_EQ(std::get<MeshShape>(posed.objects[0].shape).mesh, floorMesh);  // the same mesh, not a copy
    // The ball's cube centre follows it.
    const Sphere& s = std::get<Sphere>(posed.objects[static_cast<std::size_t>(ball)].shape);
    expectNear(posed.objects[static_cast<std::size_t>(ball)].origin, s.center);
    // Posing again at the same time changes nothing.
    EXPECT_TRUE(poseScene(scene, 0.5f, posed).empty());
}

TEST(ScenePose, ClampedAnimationStopsChangingAfterItsLastKey) {
    Scene scene = *makeBuiltinScene("light-sweep");
    scene.animation.lights[0].wrap = Wrap::Clamp;
    Scene posed = scene;
    EXPECT_EQ(poseScene(scene, 3.0f, posed).lights.size(), 1u);
    EXPECT_EQ(poseScene(scene, 4.0f, posed).lights.size(), 1u);  // the last key is at 4 s
    EXPECT_TRUE(poseScene(scene, 5.0f, posed).empty());
    EXPECT_TRUE(poseScene(scene, 9.0f, posed).empty());
}

TEST(ScenePose, BuiltinAnimatedScenesStartPosedAtTimeZero) {
    for (const char* name : {"room-moving", "orbit", "cloth", "light-sweep"}) {
        const Scene scene = *makeBuiltinScene(name);
        ASSERT_FALSE(scene.animation.empty()) << name;
        Scene posed = scene;
        EXPECT_TRUE(poseScene(scene, 0.0f, posed).empty()) << name;
        EXPECT_FALSE(poseScene(scene, 0.25f, posed).empty()) << name;
    }
}

TEST(ScenePose, ClothIsAbout90kTriangles) {
    const Scene scene = *makeBuiltinScene("cloth");
    const auto* cloth = scene.animation.forObject(scene.animation.objects[0].object);
    ASSERT_NE(cloth, nullptr);
    const auto& mesh = *std::get<MeshShape>(scene.objects[static_cast<std::size_t>(cloth->object)].shape).mesh;
    EXPECT_GT(mesh.triangles.size(), 85000u);
    EXPECT_LT(mesh.triangles.size(), 95000u);
}

}  // namespace
}  // namespace raycache
