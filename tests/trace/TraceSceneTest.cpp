#include "trace/TraceScene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "scene/MeshGenerators.h"

using namespace raycache;

namespace {

Scene oneSphere(const Vec3& center, float radius) {
    Scene s;
    s.objects.push_back(SceneObject{"ball", Sphere{center, radius}, Material{}, center});
    return s;
}

// Analytic nearest root of |o + t d - c|^2 = r^2 with t >= tNear, in double.
double analyticHit(const Vec3& o, const Vec3& d, const Vec3& c, double r, double tNear = 0.0) {
    const double ox = o.x - c.x, oy = o.y - c.y, oz = o.z - c.z;
    const double a = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    const double b = ox * d.x + oy * d.y + oz * d.z;
    const double cc = ox * ox + oy * oy + oz * oz - r * r;
    const double disc = b * b - a * cc;
    if (disc < 0) return -1;
    const double t0 = (-b - std::sqrt(disc)) / a, t1 = (-b + std::sqrt(disc)) / a;
    if (t0 >= tNear) return t0;
    if (t1 >= tNear) return t1;
    return -1;
}

}  // namespace

TEST(TraceScene, SphereHitDistanceMatchesAnalyticSolution) {
    const Vec3 c{0.5f, -0.25f, -4.0f};
    const float r = 1.25f;
    const TraceScene tracer(oneSphere(c, r));
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        // A fan of rays from the origin, some missing, some grazing.
        const float a = -0.4f + 0.8f * static_cast<float>(i) / 199.0f;
        const Vec3 d = normalize(Vec3{a, 0.1f * a, -1.0f});
        const double expected = analyticHit({0, 0, 0}, d, c, r);
        const TraceHit hit = tracer.intersect(Ray{{0, 0, 0}, d});
        if (expected < 0) {
            EXPECT_FALSE(hit.hit()) << "ray " << i;
            continue;
        }
        ASSERT_TRUE(hit.hit()) << "ray " << i;
        EXPECT_EQ(hit.objectId, 0);
        EXPECT_NEAR(hit.t, expected, 1e-4 * expected) << "ray " << i;
        ++hits;
    }
    EXPECT_GT(hits, 50);
}

TEST(TraceScene, RayFromInsideHitsTheFarSide) {
    const TraceScene tracer(oneSphere({0, 0, 0}, 2.0f));
    const TraceHit hit = tracer.intersect(Ray{{0.5f, 0, 0}, {1, 0, 0}});
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.t, 1.5f, 1e-5f);
}

TEST(TraceScene, TnearAndTfarBoundTheSearch) {
    const TraceScene tracer(oneSphere({0, 0, -5}, 1.0f));
    EXPECT_FALSE(tracer.intersect(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 3.9f}).hit());
    EXPECT_TRUE(tracer.occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 4.1f}));
    EXPECT_FALSE(tracer.occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 3.9f}));
    // Starting past the front surface finds the back one at t = 6.
    EXPECT_NEAR(tracer.intersect(Ray{{0, 0, 0}, {0, 0, -1}, 4.5f}).t, 6.0f, 1e-5f);
}

TEST(TraceScene, ObjectIdsNameSceneObjectsAndPacketsAgreeWithSingleRays) {
    Scene s = oneSphere({-2, 0, -6}, 1.0f);
    const auto box = std::make_shared<const TriangleMesh>(
        transformed(makeBox(), Transform::translate({2, 0, -6}) * Transform::scale({2, 2, 2})));
    s.objects.push_back(SceneObject{"box", MeshShape{box}, Material{}, {2, 0, -6}});
    const TraceScene tracer(s);

    std::vector<Ray> rays;
    for (int i = 0; i < 61; ++i)  // not a multiple of 8: exercises a partial packet
        rays.push_back(Ray{{0, 0, 0}, normalize(Vec3{-0.6f + 0.02f * static_cast<float>(i), 0.01f, -1.0f})});
    std::vector<TraceHit> packetHits(rays.size());
    tracer.intersectCoherent(rays, packetHits);
    bool sawSphere = false, sawBox = false;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const TraceHit single = tracer.intersect(rays[i]);
        EXPECT_EQ(single.objectId, packetHits[i].objectId) << i;
        if (single.hit()) {
            EXPECT_FLOAT_EQ(single.t, packetHits[i].t) << i;
        }
        sawSphere |= single.objectId == 0;
        sawBox |= single.objectId == 1;
    }
    EXPECT_TRUE(sawSphere);
    EXPECT_TRUE(sawBox);
    // Occlusion packets agree with single occlusion rays.
    std::vector<unsigned char> blocked(rays.size());
    tracer.occludedCoherent(rays, blocked);
    for (std::size_t i = 0; i < rays.size(); ++i)
        EXPECT_EQ(blocked[i] != 0, tracer.occluded(rays[i])) << i;
    // The box's front face is at z = -5.
    EXPECT_NEAR(tracer.intersect(Ray{{2, 0, 0}, {0, 0, -1}}).t, 5.0f, 1e-5f);
}
