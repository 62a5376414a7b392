// The tile kernel's sixteen-lane surface and shadow-ray code against the
// scalar rules it implements (surfacePointAt, LocalShading::shadowQueries), bit
// for bit, and the specular power against std::pow. The release build runs
// the copy this machine's lane level picks (AVX-512 or AVX2); the asan build, with
// RAYCACHE_BASELINE_LANES, the baseline x86-64 code.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "render/CameraRays.h"
#include "render/HitLanes.h"
#include "render/LocalShading.h"
#include "render/SpecularPower.h"
#include "render/SurfacePoint.h"

using namespace raycache;

namespace {

std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }

void expectSameBits(const Vec3& a, const Vec3& b, const char* what, int k) {
    EXPECT_EQ(bits(a.x), bits(b.x)) << what << " x, lane " << k;
    EXPECT_EQ(bits(a.y), bits(b.y)) << what << " y, lane " << k;
    EXPECT_EQ(bits(a.z), bits(b.z)) << what << " z, lane " << k;
}

Vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> g;
    return normalize(Vec3{g(rng), g(rng), g(rng)});
}

}  // namespace

TEST(HitLanes, SphereSurfacesEqualSurfacePointAt) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> coord(-30.0f, 30.0f), radius(0.05f, 8.0f), unit(-1.0f, 1.0f);
    int backFaces = 0;
    for (int round = 0; round < 2000; ++round) {
        // One sphere per call, as the kernel takes a packet's lanes object by object.
        const Sphere sphere{{coord(rng), coord(rng), coord(rng)}, radius(rng)};
        SceneObject object;
        object.shape = sphere;
        RayLanes16 rays{};
        std::vector<Ray> scalarRays(16);
        std::vector<TraceHit> hits(16);
        alignas(64) int lanes[16];
        for (int k = 0; k < 16; ++k) {
            const auto i = static_cast<std::size_t>(k);
            // Rays from outside and from inside (refracted rays leaving).
            const bool inside = k % 3 == 0;
            const Vec3 origin = inside ? sphere.center + Vec3{unit(rng), unit(rng), unit(rng)} * (0.5f * sphere.radius)
                                       : Vec3{coord(rng), coord(rng), coord(rng)};
            scalarRays[i] = Ray{origin, randomUnit(rng)};
            hits[i].t = std::fabs(coord(rng));
            setLaneRay(rays, k, scalarRays[i]);
            rays.tFar[k] = hits[i].t;
            lanes[k] = (round + k) % 7 == 0 ? 0 : -1;
        }
        SurfaceLanes16 out{};
        out.positionX[0] = -7.0f;  // a lane left out keeps what it held
        sphereSurfaceLanes16(rays, sphere, lanes, out);
        for (int k = 0; k < 16; ++k) {
            const auto i = static_cast<std::size_t>(k);
            if (!lanes[k]) {
                if (k == 0) {
                    EXPECT_EQ(out.positionX[0], -7.0f);
                }
                continue;
            }
            const SurfacePoint expected = surfacePointAt(object, scalarRays[i], hits[i], false);
            const SurfacePoint got = laneSurface(out, k);
            expectSameBits(got.position, expected.position, "position", k);
            expectSameBits(got.normal, expected.normal, "normal", k);
            expectSameBits(got.geometricNormal, expected.geometricNormal, "geometric normal", k);
            EXPECT_EQ(got.frontFace, expected.frontFace) << "lane " << k;
            backFaces += expected.frontFace ? 0 : 1;
        }
        if (HasFailure()) return;
    }
    EXPECT_GT(backFaces, 1000);  // both orientations were checked
}

TEST(HitLanes, ShadowRaysEqualScalarQueriesForEveryLightKind) {
    Scene scene;
    Light point;
    point.position = {3.0f, 9.0f, -2.0f};
    Light directional;
    directional.type = LightType::Directional;
    directional.direction = normalize(Vec3{0.3f, -1.0f, 0.2f});
    Light axis;  // a direction with zero components: their sign must survive
    axis.type = LightType::Directional;
    axis.direction = {0.0f, -1.0f, 0.0f};
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {-4.0f, 6.0f, 1.0f};
    spot.direction = normalize(Vec3{0.5f, -1.0f, 0.0f});
    spot.coneAngleDeg = 40.0f;
    spot.falloffAngleDeg = 15.0f;
    Light hardSpot = spot;  // no falloff: the step branch of smoothstep
    hardSpot.falloffAngleDeg = 0.0f;
    scene.lights = {point, directional, axis, spot, hardSpot};
    const LocalShading shading(scene);

    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(-200.0f, 200.0f), near(-0.9f, 0.9f);
    int queriesSeen = 0;
    for (int round = 0; round < 2000; ++round) {
        const int count = 1 + round % 16;
        SurfacePoint surfaces[16];
        for (int k = 0; k < count; ++k) {
            // Coordinates below 1 too, where the offset's floor of 1 decides.
            const float scale = k % 4 == 0 ? 0.01f : 1.0f;
            surfaces[k].position = Vec3{coord(rng), coord(rng), coord(rng)} * scale;
            surfaces[k].geometricNormal = randomUnit(rng);
            // A shading normal near the geometric one, as interpolated normals are.
            surfaces[k].normal = normalize(surfaces[k].geometricNormal + Vec3{near(rng), near(rng), near(rng)} * 0.3f);
        }
        SurfaceLanes16 lanes{};
        alignas(64) int selected[16];
        for (int k = 0; k < 16; ++k) {
            const SurfacePoint& sp = surfaces[k < count ? k : 0];
            lanes.positionX[k] = sp.position.x, lanes.positionY[k] = sp.position.y, lanes.positionZ[k] = sp.position.z;
            lanes.normalX[k] = sp.normal.x, lanes.normalY[k] = sp.normal.y, lanes.normalZ[k] = sp.normal.z;
            lanes.geometricX[k] = sp.geometricNormal.x, lanes.geometricY[k] = sp.geometricNormal.y;
            lanes.geometricZ[k] = sp.geometricNormal.z;
            selected[k] = k < count ? -1 : 0;
        }
        const std::size_t lightCount = scene.lights.size();
        std::vector<RayLanes16> rays(lightCount);
        std::vector<PacketLanes> traced(lightCount);
        std::vector<LightLanes16> seen(lightCount);
        for (std::size_t l = 0; l < lightCount; ++l)
            shadowRayLanes16(scene.lights[l], shading.spotCones()[l], lanes, selected, rays[l], traced[l], seen[l]);
        int written = 0, expectedTotal = 0;
        for (int k = 0; k < 16; ++k) {
            if (k >= count) {
                for (std::size_t l = 0; l < lightCount; ++l) EXPECT_EQ(traced[l].valid[k], 0) << "lane left out " << k;
                continue;
            }
            ShadowQuery expected[5];
            const int n = shading.shadowQueries(surfaces[k], expected);
            // The lights the lanes reach, in order, are the scalar queries.
            int q = 0;
            for (std::size_t l = 0; l < lightCount; ++l) {
                if (!traced[l].valid[k]) continue;
                ++written;
                ASSERT_LT(q, n) << "surface " << k;
                EXPECT_EQ(expected[q].lightIndex, static_cast<int>(l));
                Ray ray = laneRay(rays[l], k);
                ray.tNear = rays[l].tNear[k];
                ray.tFar = rays[l].tFar[k];
                expectSameBits(ray.origin, expected[q].ray.origin, "origin", k);
                expectSameBits(ray.direction, expected[q].ray.direction, "direction", k);
                EXPECT_EQ(bits(ray.tNear), bits(expected[q].ray.tNear));
                EXPECT_EQ(bits(ray.tFar), bits(expected[q].ray.tFar));
                EXPECT_EQ(bits(seen[l].strength[k]), bits(expected[q].strength));
                ++q;
            }
            EXPECT_EQ(q, n) << "surface " << k;
            expectedTotal += n;
        }
        EXPECT_EQ(written, expectedTotal);
        queriesSeen += written;
        if (HasFailure()) return;
    }
    EXPECT_GT(queriesSeen, 2000 * 8 / 2);  // lights do reach surfaces: not a vacuous comparison
}

TEST(HitLanes, SpecularPowerIsCloseToPowAndExactForSmallExponents) {
    EXPECT_EQ(specularPower(0.5f, 0.0f), 1.0f);
    EXPECT_EQ(specularPower(0.0f, 0.0f), 1.0f);
    EXPECT_EQ(specularPower(0.5f, 1.0f), 0.5f);
    EXPECT_EQ(specularPower(0.5f, 3.0f), 0.125f);
    EXPECT_EQ(specularPower(0.0f, 32.0f), 0.0f);
    // Not whole: glibc's powf.
    EXPECT_EQ(bits(specularPower(0.7f, 2.5f)), bits(std::pow(0.7f, 2.5f)));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> x(0.0f, 1.0f);
    for (int i = 0; i < 20000; ++i) {
        const float base = x(rng);
        const float exponent = static_cast<float>(i % 200);
        const float expected = std::pow(base, exponent);
        // Repeated squaring: a few ulps of relative error, far below what a display shows.
        EXPECT_NEAR(specularPower(base, exponent), expected, 1e-5f * expected + 1e-38f) << base << "^" << exponent;
    }
}

TEST(HitLanes, CameraRowsEqualSingleCameraRays) {
    const Camera camera{{0.3f, 1.7f, 12.0f}, {-0.4f, 0.2f, 0.0f}, {0.0f, 1.0f, 0.0f}, 53.0f};
    const CameraRays rays(camera, 333, 217);
    for (int y = 0; y < 217; y += 7)
        for (int x0 = 0; x0 < 333; x0 += 16) {
            const int count = std::min(16, 333 - x0);
            Ray row[16];
            rays.rowOfRays(x0, y, count, row);
            for (int k = 0; k < count; ++k) {
                const Ray expected = rays.ray(x0 + k, y);
                expectSameBits(row[k].origin, expected.origin, "origin", k);
                expectSameBits(row[k].direction, expected.direction, "direction", k);
                EXPECT_EQ(bits(row[k].tNear), bits(expected.tNear));
                EXPECT_EQ(bits(row[k].tFar), bits(expected.tFar));
            }
        }
}

TEST(HitLanes, MeshSurfacesEqualSurfacePointAt) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> coord(-10.0f, 10.0f), bary(0.0f, 1.0f);
    // Three meshes: vertex normals and uvs; neither; normals that cancel
    // (zero length when interpolated) or point against the winding.
    std::vector<SceneObject> objects(3);
    for (std::size_t m = 0; m < objects.size(); ++m) {
        auto mesh = std::make_shared<TriangleMesh>();
        for (int i = 0; i < 60; ++i) {
            mesh->positions.push_back({coord(rng), coord(rng), coord(rng)});
            if (m == 0) {
                mesh->normals.push_back(randomUnit(rng));
                mesh->uvs.push_back({bary(rng) * 4.0f, bary(rng) * 4.0f});
            }
            if (m == 2) mesh->normals.push_back(i % 3 == 0 ? Vec3{} : (i % 2 == 0 ? Vec3{0, 1, 0} : Vec3{0, -1, 0}));
        }
        for (std::uint32_t i = 0; i + 2 < 60; i += 3) mesh->triangles.push_back({i, i + 1, i + 2});
        objects[m].shape = MeshShape{mesh};
    }
    int back = 0;
    for (int round = 0; round < 1500; ++round) {
        const int count = 1 + round % 16;
        MeshHitLanes lanes{};
        RayLanes16 packet{};
        alignas(64) int selected[16];
        std::vector<Ray> rays(16);
        std::vector<TraceHit> hits(16);
        std::vector<std::size_t> which(16);
        for (int k = 0; k < count; ++k) {
            const auto i = static_cast<std::size_t>(k);
            which[i] = static_cast<std::size_t>((round + k) % 3);
            const TriangleMesh& mesh = *std::get<MeshShape>(objects[which[i]].shape).mesh;
            float u = bary(rng), v = bary(rng);
            if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
            hits[i] = TraceHit{std::fabs(coord(rng)), static_cast<int>(which[i]),
                               static_cast<int>(rng() % mesh.triangles.size()), u, v};
            rays[i] = Ray{{coord(rng), coord(rng), coord(rng)}, randomUnit(rng)};
            setLaneRay(packet, k, rays[i]);
            packet.tFar[k] = hits[i].t;
            lanes.u[k] = u, lanes.v[k] = v;
            // Made from the mesh as the kernel's records are (render/MeshShading.h).
            const auto triangle = static_cast<std::size_t>(hits[i].primitiveId);
            const TriangleUvRecord uv = uvRecordOf(mesh, triangle);
            setMeshTriangleLane(lanes, i, shadingRecordOf(mesh, triangle), !mesh.normals.empty(),
                                mesh.uvs.empty() ? nullptr : &uv);
        }
        // Lanes past `count` are left out (their records are stale or unset).
        for (int k = 0; k < 16; ++k) selected[k] = k < count ? -1 : 0;
        SurfaceLanes16 surfaces{};
        meshSurfaceLanes16(packet, lanes, selected, surfaces);
        SurfacePoint out[16];
        for (int k = 0; k < count; ++k) out[k] = laneSurface(surfaces, k);
        for (int k = 0; k < count; ++k) {
            const auto i = static_cast<std::size_t>(k);
            const SurfacePoint expected = surfacePointAt(objects[which[i]], rays[i], hits[i], true);
            expectSameBits(out[k].position, expected.position, "position", k);
            expectSameBits(out[k].normal, expected.normal, "normal", k);
            expectSameBits(out[k].geometricNormal, expected.geometricNormal, "geometric normal", k);
            EXPECT_EQ(bits(out[k].u), bits(expected.u)) << "lane " << k;
            EXPECT_EQ(bits(out[k].v), bits(expected.v)) << "lane " << k;
            EXPECT_EQ(out[k].frontFace, expected.frontFace) << "lane " << k;
            back += expected.frontFace ? 0 : 1;
        }
        if (HasFailure()) return;
    }
    EXPECT_GT(back, 1000);  // both sides of triangles were seen
}

TEST(HitLanes, CheckerAlbedoEqualsTextureSample) {
    // Texture::sample's checkerboard: floor, parity, every scale of
    // coordinate (negative, exact integers, past 2^24 where floats are even,
    // past 1e15 and NaN, which count as square 0); lanes left out keep their albedo.
    const Checkerboard pattern{Rgb{0.9f, 0.2f, 0.1f}, Rgb{0.1f, 0.3f, 0.7f}, 3.0f};
    const Texture texture = Texture::checkerboard(pattern);
    std::mt19937 rng(7);
    std::normal_distribution<float> normal;
    std::uniform_int_distribution<int> exponent(-10, 60);
    std::vector<float> values{0.0f, -0.0f, 1.0f, -1.0f, 1.0f / 3.0f, -1.0f / 3.0f, 16777216.0f, -16777218.0f,
                              16777215.0f, 33554432.0f, 1.0e15f, -2.0e15f, std::nanf(""),
                              std::numeric_limits<float>::infinity()};
    for (int i = 0; i < 4000; ++i) values.push_back(normal(rng) * std::ldexp(1.0f, exponent(rng)));
    int wrong = 0;
    for (std::size_t base = 0; base + 16 <= values.size(); base += 16) {
        SurfaceLanes16 surfaces{};
        alignas(64) int lanes[16];
        for (int k = 0; k < 16; ++k) {
            surfaces.u[k] = values[base + static_cast<std::size_t>(k)];
            surfaces.v[k] = values[(base * 7 + static_cast<std::size_t>(k) * 13) % values.size()];
            surfaces.albedoR[k] = surfaces.albedoG[k] = surfaces.albedoB[k] = -1.0f;
            lanes[k] = k % 5 == 0 ? 0 : -1;
        }
        checkerAlbedoLanes16(pattern, lanes, surfaces);
        for (int k = 0; k < 16; ++k) {
            const Rgb expected = lanes[k] ? texture.sample(surfaces.u[k], surfaces.v[k]) : Rgb{-1.0f};
            if ((bits(surfaces.albedoR[k]) != bits(expected.r) || bits(surfaces.albedoG[k]) != bits(expected.g) ||
                 bits(surfaces.albedoB[k]) != bits(expected.b)) &&
                ++wrong <= 5)
                ADD_FAILURE() << "u " << surfaces.u[k] << " v " << surfaces.v[k] << " lane " << k;
        }
    }
    EXPECT_EQ(wrong, 0);
}
