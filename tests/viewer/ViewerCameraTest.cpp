// The interactive camera: starts exactly where the scene's camera is, and
// orbit / look / fly / zoom move it as their names promise.
#include "viewer/ViewerCamera.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace raycache;

namespace {

void expectNear(const Vec3& a, const Vec3& b, float tolerance = 1e-4f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

Camera sceneCamera() {
    Camera c;
    c.position = {3.0f, 2.0f, 10.0f};
    c.lookAt = {0.5f, 0.0f, -1.0f};
    c.verticalFovDeg = 50.0f;
    return c;
}

}  // namespace

TEST(ViewerCamera, StartsAtTheGivenCamera) {
    const ViewerCamera vc(sceneCamera());
    const Camera c = vc.camera();
    expectNear(c.position, sceneCamera().position);
    expectNear(c.lookAt, sceneCamera().lookAt);
    EXPECT_EQ(c.verticalFovDeg, 50.0f);
}

TEST(ViewerCamera, OrbitKeepsTargetAndDistanceAndMovesToTheRight) {
    ViewerCamera vc(sceneCamera());
    const Camera before = vc.camera();
    const Vec3 right = normalize(cross(before.lookAt - before.position, before.up));
    vc.orbit(10.0f, 0.0f);
    const Camera after = vc.camera();
    expectNear(after.lookAt, before.lookAt);
    EXPECT_NEAR(length(after.position - after.lookAt), length(before.position - before.lookAt), 1e-4f);
    EXPECT_GT(dot(after.position - before.position, right), 0.1f);
    EXPECT_NEAR(after.position.y, before.position.y, 1e-4f);  // yaw is about the up axis
    vc.orbit(0.0f, 20.0f);
    EXPECT_GT(vc.camera().position.y, after.position.y);  // pitch > 0 raises the camera
}

TEST(ViewerCamera, OrbitStopsShortOfThePole) {
    ViewerCamera vc(sceneCamera());
    vc.orbit(0.0f, 500.0f);
    const Camera c = vc.camera();
    const Vec3 f = normalize(c.lookAt - c.position);
    EXPECT_GT(std::fabs(dot(f, c.up)), 0.99f);
    EXPECT_LT(std::fabs(dot(f, c.up)), 0.99999f);  // never parallel to up: the image stays defined
}

TEST(ViewerCamera, LookTurnsAboutThePositionAndFlyTranslates) {
    ViewerCamera vc(sceneCamera());
    const Camera before = vc.camera();
    const Vec3 right = normalize(cross(before.lookAt - before.position, before.up));
    vc.look(15.0f, 0.0f);
    const Camera turned = vc.camera();
    expectNear(turned.position, before.position);
    EXPECT_GT(dot(turned.lookAt - before.lookAt, right), 0.1f);  // turned right

    const Vec3 forward = normalize(turned.lookAt - turned.position);
    vc.fly(2.0f, 0.0f, 0.0f);
    expectNear(vc.camera().position, turned.position + forward * 2.0f);
    vc.fly(0.0f, 0.0f, 1.5f);
    expectNear(vc.camera().position, turned.position + forward * 2.0f + Vec3{0, 1.5f, 0});
}

TEST(ViewerCamera, ZoomDolliesTowardTheTargetButNotThrough) {
    ViewerCamera vc(sceneCamera());
    const float d = vc.distance();
    vc.zoom(0.5f);
    EXPECT_NEAR(vc.distance(), 0.5f * d, 1e-4f);
    expectNear(vc.camera().lookAt, sceneCamera().lookAt);
    for (int i = 0; i < 200; ++i) vc.zoom(0.5f);
    EXPECT_GT(vc.distance(), 0.0f);
    vc.zoom(0.0f);  // ignored
    vc.zoom(std::nanf(""));
    EXPECT_GT(vc.distance(), 0.0f);
}

TEST(ViewerCamera, SetCameraTakesOverAnotherView) {
    ViewerCamera vc(sceneCamera());
    Camera other;
    other.position = {-4.0f, 1.0f, 2.0f};
    other.lookAt = {1.0f, 1.5f, -3.0f};
    other.verticalFovDeg = 30.0f;
    vc.setCamera(other);
    expectNear(vc.camera().position, other.position);
    expectNear(vc.camera().lookAt, other.lookAt);
    EXPECT_EQ(vc.camera().verticalFovDeg, 30.0f);
}
