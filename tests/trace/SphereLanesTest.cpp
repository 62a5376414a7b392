// The sixteen-lane sphere root against the scalar one, bit for bit: the
// packet callbacks use the first, single rays and the grids the second, so a
// sphere hit's distance must not depend on which ran. The release build
// runs the copy this machine's lane level picks (AVX-512 or AVX2); the asan build, with
// RAYCACHE_BASELINE_LANES, the baseline x86-64 code.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "trace/SphereIntersection.h"
#include "trace/SphereLanes.h"

using namespace raycache;

namespace {

struct Packet {
    float ox[16], oy[16], oz[16], dx[16], dy[16], dz[16], tnear[16], tfar[16];
    int active[16];
    RayLanePointers pointers() const { return {ox, oy, oz, dx, dy, dz, tnear, tfar}; }
};

// Checks every lane of `p` against sphereRoot; returns the lanes that hit.
int expectLanesEqualScalar(const Sphere& sphere, const Packet& p) {
    float t[16];
    sphereRoots16(sphere, p.pointers(), p.active, t);
    int hits = 0;
    for (int k = 0; k < 16; ++k) {
        const float expected = p.active[k] ? sphereRoot(sphere, p.ox[k], p.oy[k], p.oz[k], p.dx[k], p.dy[k], p.dz[k],
                                                        p.tnear[k], p.tfar[k])
                                           : -1.0f;
        // A miss is any negative value in both; a hit the same bits.
        if (expected < 0.0f || std::isnan(expected)) {
            EXPECT_FALSE(t[k] >= 0.0f) << "lane " << k << " hit at " << t[k] << ", scalar missed";
        } else {
            EXPECT_EQ(std::bit_cast<std::uint32_t>(t[k]), std::bit_cast<std::uint32_t>(expected))
                << "lane " << k << ": " << t[k] << " vs scalar " << expected;
            ++hits;
        }
    }
    return hits;
}

}  // namespace

TEST(SphereLanes, EqualsScalarRootBitForBitOnRandomRays) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-20.0f, 20.0f), unit(-1.0f, 1.0f), radius(0.01f, 5.0f);
    int hits = 0, lanes = 0;
    for (int round = 0; round < 4000; ++round) {
        const Sphere sphere{{coord(rng), coord(rng), coord(rng)}, radius(rng)};
        Packet p;
        for (int k = 0; k < 16; ++k) {
            // Half the rays aim at a point near the sphere, so both roots,
            // grazing rays and origins inside all occur.
            const Vec3 origin = round % 3 == 0 ? sphere.center + Vec3{unit(rng), unit(rng), unit(rng)} * sphere.radius
                                               : Vec3{coord(rng), coord(rng), coord(rng)};
            const Vec3 target = k % 2 == 0 ? sphere.center + Vec3{unit(rng), unit(rng), unit(rng)} * sphere.radius
                                           : Vec3{coord(rng), coord(rng), coord(rng)};
            Vec3 d = target - origin;
            if (round % 2 == 0) d = normalize(d);  // unnormalized directions too (instances scale them)
            p.ox[k] = origin.x, p.oy[k] = origin.y, p.oz[k] = origin.z;
            p.dx[k] = d.x, p.dy[k] = d.y, p.dz[k] = d.z;
            p.tnear[k] = k % 4 == 0 ? 0.5f : 0.0f;
            p.tfar[k] = k % 5 == 0 ? 3.0f : std::numeric_limits<float>::infinity();
            p.active[k] = k % 7 == 6 ? 0 : -1;
        }
        hits += expectLanesEqualScalar(sphere, p);
        lanes += 16;
        if (HasFailure()) return;
    }
    // Not vacuous: a good share of the lanes hit (both roots and bounded segments occur).
    EXPECT_GT(hits, lanes / 10);
}

TEST(SphereLanes, EdgeCasesEqualScalar) {
    const Sphere sphere{{1.0f, 2.0f, -3.0f}, 1.5f};
    Packet p;
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    // Tangent, from the centre, behind, zero direction, NaN, at the surface, huge distance, tiny segment.
    const float rays[16][8] = {
        {-5, 3.5f, -3, 1, 0, 0, 0, inf},  {1, 2, -3, 0, 0, 1, 0, inf},        {1, 2, 5, 0, 0, 1, 0, inf},
        {0, 0, 0, 0, 0, 0, 0, inf},       {nan, 0, 0, 1, 0, 0, 0, inf},       {1, 2, -1.5f, 0, 0, -1, 0, inf},
        {1e6f, 2, -3, -1, 0, 0, 0, inf},  {1, 2, 5, 0, 0, -1, 0, 1e-3f},      {1, 2, 5, 0, 0, -1, 6.5f, 6.5f},
        {1, 2, 5, 0, 0, -1, 6.5f, 9.5f},  {1, 2, 5, 0, 0, -1, 9.5f, inf},     {1, 2, 5, 0, 0, -2, 0, inf},
        {-4, -2, 1, 1, 0.8f, -0.8f, 0, inf}, {1, 2, 5, 0, 0, -1, 0, nan},     {1, 2, 5, 1e-20f, 0, -1, 0, inf},
        {1, 3.5f, 5, 0, 0, -1, 0, inf}};
    for (int k = 0; k < 16; ++k) {
        p.ox[k] = rays[k][0], p.oy[k] = rays[k][1], p.oz[k] = rays[k][2];
        p.dx[k] = rays[k][3], p.dy[k] = rays[k][4], p.dz[k] = rays[k][5];
        p.tnear[k] = rays[k][6], p.tfar[k] = rays[k][7];
        p.active[k] = -1;
    }
    EXPECT_GE(expectLanesEqualScalar(sphere, p), 6);
}
