// hitOnPrimitive against Embree (the tracer): inside a primitive both must
// report the same hit; outside a triangle's edges it continues the plane
// within kTriangleSlack and misses beyond; a sphere is missed where Embree
// misses it.
#include "render/HitOnPrimitive.h"

#include <gtest/gtest.h>

#include <memory>

#include "trace/TraceScene.h"

using namespace raycache;

namespace {

Scene oneObject(SceneObject object) {
    Scene s;
    s.objects.push_back(std::move(object));
    return s;
}

// One triangle (0,0,-5), (2,0,-5), (0,2,-6): tilted, so depth varies over it.
SceneObject tiltedTriangle() {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->positions = {{0, 0, -5}, {2, 0, -5}, {0, 2, -6}};
    mesh->triangles = {{0, 1, 2}};
    return SceneObject{"tri", MeshShape{mesh}, Material{}, {0, 0, -5}};
}

// A ray from the origin through the triangle's point of barycentrics (u, v).
Ray rayThrough(float u, float v) {
    const Vec3 p = Vec3{0, 0, -5} * (1 - u - v) + Vec3{2, 0, -5} * u + Vec3{0, 2, -6} * v;
    return Ray{{0, 0, 0}, normalize(p)};
}

}  // namespace

TEST(HitOnPrimitive, InsideATriangleItIsTheTracersHit) {
    const Scene scene = oneObject(tiltedTriangle());
    const TraceScene tracer(scene);
    int checked = 0;
    for (int i = 1; i < 10; ++i)
        for (int j = 1; i + j < 10; ++j) {
            const Ray ray = rayThrough(0.1f * static_cast<float>(i), 0.1f * static_cast<float>(j));
            const TraceHit expected = tracer.intersect(ray);
            ASSERT_TRUE(expected.hit());
            const auto hit = hitOnPrimitive(scene.objects[0], 0, 0, ray, expected.t);
            ASSERT_TRUE(hit.has_value()) << i << "," << j;
            EXPECT_EQ(hit->objectId, 0);
            EXPECT_EQ(hit->primitiveId, 0);
            EXPECT_NEAR(hit->t, expected.t, 1e-5f * expected.t);
            EXPECT_NEAR(hit->u, expected.u, 1e-5f);
            EXPECT_NEAR(hit->v, expected.v, 1e-5f);
            ++checked;
        }
    EXPECT_EQ(checked, 36);
}

TEST(HitOnPrimitive, OutsideATriangleItContinuesThePlaneWithinTheSlack) {
    const Scene scene = oneObject(tiltedTriangle());
    const TraceScene tracer(scene);
    // Just outside the edge u = 0: the tracer misses, the plane continues.
    const Ray near = rayThrough(-0.2f, 0.3f);
    EXPECT_FALSE(tracer.intersect(near).hit());
    const auto hit = hitOnPrimitive(scene.objects[0], 0, 0, near, 5.0f);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->u, -0.2f, 1e-5f);
    EXPECT_NEAR(hit->v, 0.3f, 1e-5f);
    const Vec3 onPlane = near.origin + near.direction * hit->t;
    const Vec3 expected = Vec3{0, 0, -5} * 0.9f + Vec3{2, 0, -5} * -0.2f + Vec3{0, 2, -6} * 0.3f;
    EXPECT_NEAR(length(onPlane - expected), 0.0f, 1e-5f);
    // Beyond the slack, on every side: missed.
    EXPECT_FALSE(hitOnPrimitive(scene.objects[0], 0, 0, rayThrough(-kTriangleSlack - 0.1f, 0.3f), 5.0f));
    EXPECT_FALSE(hitOnPrimitive(scene.objects[0], 0, 0, rayThrough(0.3f, -kTriangleSlack - 0.1f), 5.0f));
    EXPECT_FALSE(hitOnPrimitive(scene.objects[0], 0, 0, rayThrough(0.9f, 0.7f + kTriangleSlack), 5.0f));
    // A ray pointing away from the plane, and one within it: missed.
    EXPECT_FALSE(hitOnPrimitive(scene.objects[0], 0, 0, Ray{{0, 0, 0}, {0, 0, 1}}, 5.0f));
    EXPECT_FALSE(hitOnPrimitive(scene.objects[0], 0, 0, Ray{{0, 0, -5}, {1, 0, 0}}, 5.0f));
    // A primitive the mesh does not have.
    EXPECT_FALSE(hitOnPrimitive(scene.objects[0], 0, 1, rayThrough(0.2f, 0.2f), 5.0f));
}

TEST(HitOnPrimitive, OnASphereItIsTheTracersHitFromOutsideAndInside) {
    const Vec3 c{0.5f, -0.25f, -4.0f};
    const Scene scene = oneObject(SceneObject{"ball", Sphere{c, 1.25f}, Material{}, c});
    const TraceScene tracer(scene);
    int hits = 0, misses = 0;
    for (int i = 0; i < 200; ++i) {
        const float a = -0.5f + 1.0f * static_cast<float>(i) / 199.0f;
        const Ray ray{{0, 0, 0}, normalize(Vec3{a, 0.1f * a, -1.0f})};
        const TraceHit expected = tracer.intersect(ray);
        const auto hit = hitOnPrimitive(scene.objects[0], 0, 0, ray, expected.hit() ? expected.t : 4.0f);
        EXPECT_EQ(hit.has_value(), expected.hit()) << "ray " << i;
        if (!expected.hit() || !hit) {
            ++misses;
            continue;
        }
        EXPECT_NEAR(hit->t, expected.t, 1e-5f * expected.t) << "ray " << i;
        ++hits;
    }
    EXPECT_GT(hits, 50);
    EXPECT_GT(misses, 20);
    // From inside, a point on the far wall stays on the far wall.
    const Ray inside{c, normalize(Vec3{0.3f, 0.2f, -1.0f})};
    const TraceHit wall = tracer.intersect(inside);
    ASSERT_TRUE(wall.hit());
    const auto hit = hitOnPrimitive(scene.objects[0], 0, 0, inside, wall.t);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->t, 1.25f, 1e-5f);
}
