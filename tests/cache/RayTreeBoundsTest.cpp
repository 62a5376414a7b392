// The geometric tests behind per-block invalidation (cache/RayTreeBounds.h),
// against brute force: any point found by sampling the hull, sweep or ray
// set that lies in the box must make the test answer "meets" (the direction
// that keeps cached texels from going stale), and hand-made cases check that
// clearly separated boxes are not reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "cache/RayTreeBounds.h"

namespace raycache {
namespace {

Box3 box(const Vec3& lo, const Vec3& hi) {
    Box3 b;
    b.add(lo);
    b.add(hi);
    return b;
}

bool contains(const Box3& b, const Vec3& p) {
    return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z && p.z <= b.hi.z;
}

Vec3 lerp(const Box3& b, float u, float v, float w) {
    return {b.lo.x + (b.hi.x - b.lo.x) * u, b.lo.y + (b.hi.y - b.lo.y) * v, b.lo.z + (b.hi.z - b.lo.z) * w};
}

struct RandomCase {
    std::mt19937 rng;
    explicit RandomCase(unsigned seed) : rng(seed) {}
    float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(rng); }
    Vec3 point(float r) { return {uniform(-r, r), uniform(-r, r), uniform(-r, r)}; }
    Box3 randomBox(float r, float size) {
        const Vec3 c = point(r);
        const Vec3 h{uniform(0.0f, size), uniform(0.0f, size), uniform(0.0f, size)};
        return box(c - h, c + h);
    }
};

// One random case: the box, the test's answer, and a sampler of the set's points.
struct SampledCase {
    Box3 target;
    bool reported;
    std::function<Vec3(RandomCase&)> samplePoint;
};

// 3000 random cases from makeCase: whenever one of 400 sampled points of
// the set lies in the box, the test must have answered "meets". The sampler
// must find some meetings and the test must say "no" to some boxes, or the
// check proves nothing.
void expectNoMissedMeeting(unsigned seed, const std::function<SampledCase(RandomCase&)>& makeCase) {
    RandomCase random(seed);
    int meetings = 0, reportedCount = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const SampledCase c = makeCase(random);
        reportedCount += c.reported ? 1 : 0;
        bool found = false;
        for (int k = 0; k < 400 && !found; ++k) found = contains(c.target, c.samplePoint(random));
        if (found) {
            ++meetings;
            EXPECT_TRUE(c.reported) << "trial " << trial;
        }
    }
    EXPECT_GT(meetings, 30);
    EXPECT_LT(reportedCount, 3000);
}

Vec3 pointIn(const Box3& b, RandomCase& random) {
    return lerp(b, random.uniform(0, 1), random.uniform(0, 1), random.uniform(0, 1));
}

TEST(RayTreeBounds, HullTestNeverMissesASampledMeeting) {
    expectNoMissedMeeting(7, [](RandomCase& random) {
        const Box3 points = random.randomBox(4.0f, 2.0f);
        const Vec3 apex = random.point(6.0f);
        const Box3 target = random.randomBox(4.0f, 1.0f);
        return SampledCase{target, boxMeetsHull(target, points, apex), [=](RandomCase& r) {
                               return apex + (pointIn(points, r) - apex) * r.uniform(0, 1);
                           }};
    });
}

TEST(RayTreeBounds, SegmentsTestNeverMissesASampledMeeting) {
    expectNoMissedMeeting(5, [](RandomCase& random) {
        const Box3 starts = random.randomBox(4.0f, 1.0f);
        const Box3 ends = random.randomBox(4.0f, 1.5f);
        const Box3 target = random.randomBox(4.0f, 1.0f);
        return SampledCase{target, boxMeetsSegments(target, starts, ends), [=](RandomCase& r) {
                               const Vec3 a = pointIn(starts, r);
                               return a + (pointIn(ends, r) - a) * r.uniform(0, 1);
                           }};
    });
}

TEST(RayTreeBounds, SweepTestNeverMissesASampledMeeting) {
    expectNoMissedMeeting(11, [](RandomCase& random) {
        const Box3 points = random.randomBox(4.0f, 2.0f);
        const Vec3 direction = normalize(random.point(1.0f) + Vec3{0.0f, 1e-3f, 0.0f});
        const Box3 target = random.randomBox(6.0f, 1.0f);
        return SampledCase{target, boxMeetsSweep(target, points, direction), [=](RandomCase& r) {
                               return pointIn(points, r) + direction * r.uniform(0, 20);
                           }};
    });
}

TEST(RayTreeBounds, RaysTestNeverMissesASampledMeeting) {
    expectNoMissedMeeting(13, [](RandomCase& random) {
        const Box3 origins = random.randomBox(3.0f, 1.0f);
        const Vec3 d0 = normalize(random.point(1.0f) + Vec3{1e-3f, 0.0f, 0.0f});
        Box3 directions = box(d0, d0);
        directions.add(normalize(d0 + random.point(0.2f)));
        const Box3 target = random.randomBox(6.0f, 1.0f);
        return SampledCase{target, boxMeetsRays(target, origins, directions), [=](RandomCase& r) {
                               return pointIn(origins, r) + pointIn(directions, r) * r.uniform(0, 20);
                           }};
    });
}

// The ball tests (a moving sphere against the same sets), against the
// distance from the ball's centre to the set. For each parameter value the
// set's slice is a box, whose nearest point to the centre is the centre
// clamped into it. Every set here is a box whose corners move linearly with
// the parameter, so the pairs (s, x) with x in the slice at s form a convex
// set, and the distance from the centre to the slice is a convex function of
// s: a golden-section search finds its minimum, to far below the 1e-3 margin,
// in under two hundred evaluations where sampling needed twenty thousand. A ball
// nearer than its radius must be reported, one farther than its radius plus
// 1e-3 must not (the tests exist to be tighter than the box tests).
struct BallCase {
    Vec3 centre;
    float radius;
    bool reported;
    std::function<Box3(double)> slice;  // the set at parameter s in [0, sMax]
    double sMax;
};

double distanceToSlice(const BallCase& c, double s) {
    const Box3 b = c.slice(s);
    double sum = 0.0;
    for (int a = 0; a < 3; ++a) {
        const double gap = std::max({static_cast<double>(b.lo[a]) - c.centre[a], 0.0,
                                     static_cast<double>(c.centre[a]) - b.hi[a]});
        sum += gap * gap;
    }
    return std::sqrt(sum);
}

double nearestDistance(const BallCase& c) {
    const double inversePhi = (std::sqrt(5.0) - 1.0) / 2.0;
    double lo = 0.0, hi = c.sMax;
    double nearest = std::min(distanceToSlice(c, lo), distanceToSlice(c, hi));
    for (int step = 0; step < 100 && hi - lo > 1e-12; ++step) {
        const double a = hi - (hi - lo) * inversePhi, b = lo + (hi - lo) * inversePhi;
        const double fa = distanceToSlice(c, a), fb = distanceToSlice(c, b);
        nearest = std::min({nearest, fa, fb});
        if (fa <= fb)
            hi = b;
        else
            lo = a;
    }
    return nearest;
}

void expectBallTestExact(unsigned seed, const std::function<BallCase(RandomCase&)>& makeCase) {
    RandomCase random(seed);
    int meetings = 0, misses = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const BallCase c = makeCase(random);
        const double distance = nearestDistance(c);
        if (distance <= c.radius) {
            ++meetings;
            EXPECT_TRUE(c.reported) << "trial " << trial << ": distance " << distance << ", radius " << c.radius;
        } else if (distance > c.radius + 1e-3) {
            ++misses;
            EXPECT_FALSE(c.reported) << "trial " << trial << ": distance " << distance << ", radius " << c.radius;
        }
    }
    EXPECT_GT(meetings, 20);
    EXPECT_GT(misses, 20);
}

Box3 movedBox(const Box3& from, const Box3& to, double s) {
    const auto f = static_cast<float>(s);
    return box(from.lo + (to.lo - from.lo) * f, from.hi + (to.hi - from.hi) * f);
}

TEST(RayTreeBounds, BallTestsFindTheDistanceToTheSet) {
    expectBallTestExact(17, [](RandomCase& random) {  // shadow rays toward a point light
        const Box3 points = random.randomBox(4.0f, 2.0f);
        const Vec3 apex = random.point(6.0f), centre = random.point(4.0f);
        const float radius = random.uniform(0.1f, 1.5f);
        return BallCase{centre, radius, ballMeetsHull(centre, radius, points, apex),
                        [=](double s) { return movedBox(points, box(apex, apex), s); }, 1.0};
    });
    expectBallTestExact(19, [](RandomCase& random) {  // traced segments
        const Box3 starts = random.randomBox(4.0f, 1.0f), ends = random.randomBox(4.0f, 1.5f);
        const Vec3 centre = random.point(4.0f);
        const float radius = random.uniform(0.1f, 1.5f);
        return BallCase{centre, radius, ballMeetsSegments(centre, radius, starts, ends),
                        [=](double s) { return movedBox(starts, ends, s); }, 1.0};
    });
    expectBallTestExact(23, [](RandomCase& random) {  // shadow rays toward a directional light
        const Box3 points = random.randomBox(4.0f, 2.0f);
        const Vec3 direction = normalize(random.point(1.0f) + Vec3{0.0f, 1e-3f, 0.0f});
        const Vec3 centre = random.point(6.0f);
        const float radius = random.uniform(0.1f, 1.5f);
        return BallCase{centre, radius, ballMeetsSweep(centre, radius, points, direction),
                        [=](double s) {
                            const Vec3 step = direction * static_cast<float>(s);
                            return box(points.lo + step, points.hi + step);
                        },
                        40.0};
    });
    expectBallTestExact(29, [](RandomCase& random) {  // escaped rays
        const Box3 origins = random.randomBox(4.0f, 1.0f);
        const Vec3 d0 = normalize(random.point(1.0f) + Vec3{1e-3f, 0.0f, 0.0f});
        Box3 directions = box(d0, d0);
        directions.add(normalize(d0 + random.point(0.2f)));
        const Vec3 centre = random.point(5.0f);
        const float radius = random.uniform(0.1f, 1.5f);
        return BallCase{centre, radius, ballMeetsRays(centre, radius, origins, directions),
                        [=](double t) {
                            const auto f = static_cast<float>(t);
                            return box(origins.lo + directions.lo * f, origins.hi + directions.hi * f);
                        },
                        40.0};
    });
}

TEST(RayTreeBounds, BallAgainstRaysWhoseDirectionsHoldZeroKeepsTheBoxAnswer) {
    // Directions spanning both signs on every axis: no face of the set ever
    // moves away, so the answer is the box test's.
    const Box3 origins = box({0, 0, 0}, {0.1f, 0.1f, 0.1f});
    const Box3 directions = box({-1, -1, -1}, {1, 1, 1});
    EXPECT_TRUE(ballMeetsRays({5, 5, 5}, 0.5f, origins, directions));
    const Box3 outward = box({0.5f, -0.1f, -0.1f}, {1.0f, 0.1f, 0.1f});
    EXPECT_FALSE(ballMeetsRays({-5, 0, 0}, 0.5f, origins, outward));
}

TEST(RayTreeBounds, SeparatedBoxesAreNotReported) {
    const Box3 points = box({-1, -1, -1}, {1, 1, 1});
    // Light above, box far to the side: no shadow ray passes it.
    EXPECT_FALSE(boxMeetsHull(box({5, 2, -1}, {6, 3, 1}), points, {0, 10, 0}));
    // The same box between the points and the light is reported.
    EXPECT_TRUE(boxMeetsHull(box({-0.5f, 4, -0.5f}, {0.5f, 5, 0.5f}), points, {0, 10, 0}));
    // Beyond the light: shadow rays stop at the light.
    EXPECT_FALSE(boxMeetsHull(box({-0.5f, 11, -0.5f}, {0.5f, 12, 0.5f}), points, {0, 10, 0}));
    // Directional light travelling down (-y): shadow rays go up, forever.
    EXPECT_TRUE(boxMeetsSweep(box({-0.5f, 50, -0.5f}, {0.5f, 51, 0.5f}), points, {0, 1, 0}));
    EXPECT_FALSE(boxMeetsSweep(box({-0.5f, -5, -0.5f}, {0.5f, -4, 0.5f}), points, {0, 1, 0}));
    // Segments from a box at the origin to a box far along +x+y: a box on
    // that diagonal is reached, one in the corner of the pair's bounding box is not.
    const Box3 far = box({9, 9, -1}, {11, 11, 1});
    EXPECT_TRUE(boxMeetsSegments(box({4.5f, 4.5f, -0.5f}, {5.5f, 5.5f, 0.5f}), points, far));
    EXPECT_FALSE(boxMeetsSegments(box({8, -1, -0.5f}, {9, 0, 0.5f}), points, far));
    // Rays leaving along +x do not reach a box behind them.
    const Box3 directions = box({0.9f, -0.1f, -0.1f}, {1.0f, 0.1f, 0.1f});
    EXPECT_TRUE(boxMeetsRays(box({10, -1, -1}, {11, 1, 1}), points, directions));
    EXPECT_FALSE(boxMeetsRays(box({-11, -1, -1}, {-10, 1, 1}), points, directions));
}

TEST(RayTreeBounds, MayMeetCombinesSegmentsEscapesAndShadowRays) {
    std::vector<Light> lights(1);
    lights[0].position = {0, 10, 0};
    RayTreeBounds bounds;
    bounds.addSegment({-1, 0, 0}, {1, 0, 0});
    const Box3 between = box({-0.2f, 5, -0.2f}, {0.2f, 6, 0.2f});
    EXPECT_FALSE(bounds.mayMeet(between, lights));  // no shadow rays
    bounds.shaded = true;
    bounds.addShadowRay({0, 0, 0}, 0, true);
    EXPECT_TRUE(bounds.mayMeet(between, lights));
    // Only shadow rays from where they start: none passes far to the left.
    EXPECT_FALSE(bounds.mayMeet(box({-3.2f, 5, -0.2f}, {-2.8f, 6, 0.2f}), lights));
    EXPECT_TRUE(bounds.mayMeet(box({0, -0.1f, -0.1f}, {0.1f, 0.1f, 0.1f}), lights));  // on the segment
    RayTreeBounds escaping;
    escaping.addEscape({0, 0, 0}, {0, 0, 1});
    EXPECT_TRUE(escaping.mayMeet(box({-1, -1, 30}, {1, 1, 31}), lights));
    EXPECT_FALSE(escaping.mayMeet(box({-1, -1, -31}, {1, 1, -30}), lights));
    RayTreeBounds everything;
    everything.dependsOnEverything = true;
    EXPECT_TRUE(everything.mayMeet(box({100, 100, 100}, {101, 101, 101}), lights));
}

// A shadow ray that reached its light can only be stopped by what a change
// put on it; one that was stopped can only be freed by what the change took
// away (the stopper stays otherwise). Each is tested against that pose only.
TEST(RayTreeBounds, ShadowRaysAreTestedAgainstThePoseThatCanChangeTheirAnswer) {
    std::vector<Light> lights(1);
    lights[0].position = {0, 10, 0};
    const Box3 onTheRay = box({-0.2f, 5, -0.2f}, {0.2f, 6, 0.2f});
    RayTreeBounds lit;
    lit.shaded = true;
    lit.addShadowRay({0, 0, 0}, 0, true);
    EXPECT_TRUE(lit.mayMeet(onTheRay, lights, RegionPose::After));
    EXPECT_FALSE(lit.mayMeet(onTheRay, lights, RegionPose::Before));
    EXPECT_TRUE(lit.mayMeet(onTheRay, lights, RegionPose::Either));
    RayTreeBounds blocked;
    blocked.shaded = true;
    blocked.addShadowRay({0, 0, 0}, 0, false);
    EXPECT_TRUE(blocked.mayMeet(onTheRay, lights, RegionPose::Before));
    EXPECT_FALSE(blocked.mayMeet(onTheRay, lights, RegionPose::After));
    EXPECT_TRUE(blocked.mayMeetBall({0, 5.5f, 0}, 0.3f, onTheRay, lights, RegionPose::Before));
    EXPECT_FALSE(blocked.mayMeetBall({0, 5.5f, 0}, 0.3f, onTheRay, lights, RegionPose::After));
    RayTreeBounds unknown;
    unknown.shaded = true;
    unknown.addShadowRaysOfUnknownAnswer({0, 0, 0});
    EXPECT_TRUE(unknown.mayMeet(onTheRay, lights, RegionPose::Before));
    EXPECT_TRUE(unknown.mayMeet(onTheRay, lights, RegionPose::After));
    // Ray off to the side: neither pose reaches it.
    EXPECT_FALSE(unknown.mayMeet(box({-3.2f, 5, -0.2f}, {-2.8f, 6, 0.2f}), lights, RegionPose::Either));
    // Each kind only toward the lights it went to: lit toward light 0,
    // stopped toward light 1; a box on the way to light 1 can only free it.
    lights.resize(2);
    lights[1].position = {10, 0, 0};
    const Box3 towardSecond = box({4.8f, -0.2f, -0.2f}, {5.2f, 0.2f, 0.2f});
    RayTreeBounds both;
    both.shaded = true;
    both.addShadowRay({0, 0, 0}, 0, true);
    both.addShadowRay({0, 0, 0}, 1, false);
    EXPECT_FALSE(both.mayMeet(towardSecond, lights, RegionPose::After));
    EXPECT_TRUE(both.mayMeet(towardSecond, lights, RegionPose::Before));
    EXPECT_FALSE(both.mayMeet(onTheRay, lights, RegionPose::Before));
    EXPECT_TRUE(both.mayMeet(onTheRay, lights, RegionPose::After));
}

// "Every stopped shadow ray meets the ball" lets a block keep texels that a
// moving ball shadowed before and still shadows: it must never claim that of
// a box one of whose points sends a ray past the ball (sampled), and it must
// claim it for some boxes, or it keeps nothing.
TEST(RayTreeBounds, BlockedRaysAllMeetBallNeverClaimsASampledRayThatMissesIt) {
    RandomCase random(31);
    int claimed = 0, refused = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        std::vector<Light> lights(1);
        const bool directional = trial % 3 == 0;
        if (directional) {
            lights[0].type = LightType::Directional;
            lights[0].direction = normalize(Vec3{random.uniform(-0.3f, 0.3f), -1.0f, random.uniform(-0.3f, 0.3f)});
        } else {
            lights[0].position = Vec3{random.uniform(-1, 1), 10.0f, random.uniform(-1, 1)};
        }
        const Vec3 centre{random.uniform(-1, 1), random.uniform(2, 6), random.uniform(-1, 1)};
        const float radius = random.uniform(0.3f, 2.0f);
        RayTreeBounds bounds;
        bounds.shaded = true;
        const Box3 origins = random.randomBox(1.5f, 0.8f);
        bounds.addShadowRay(origins.lo, 0, false);
        bounds.addShadowRay(origins.hi, 0, false);
        const bool claim = bounds.blockedRaysAllMeetBall(centre, radius, 0.0f, lights);
        (claim ? claimed : refused) += 1;
        if (!claim) continue;
        for (int k = 0; k < 200; ++k) {
            const Vec3 p = pointIn(origins, random);
            const Vec3 end = directional ? p - lights[0].direction * 100.0f : lights[0].position;
            // Nearest point of the segment to the centre.
            const Vec3 d = end - p;
            const float s = std::clamp(dot(centre - p, d) / dot(d, d), 0.0f, 1.0f);
            EXPECT_LE(length(p + d * s - centre), radius * 1.0001f) << "trial " << trial;
        }
    }
    EXPECT_GT(claimed, 30);
    EXPECT_GT(refused, 30);
    // A light inside the clearance is never claimed: the ray could stop short of the surface.
    std::vector<Light> inside(1);
    inside[0].position = {0, 3.5f, 0};
    RayTreeBounds under;
    under.shaded = true;
    under.addShadowRay({0, 0, 0}, 0, false);
    EXPECT_TRUE(under.blockedRaysAllMeetBall({0, 3, 0}, 1.0f, 0.0f, inside));
    EXPECT_FALSE(under.blockedRaysAllMeetBall({0, 3, 0}, 1.0f, 1.1f, inside));
}

}  // namespace
}  // namespace raycache
