// The tile kernel's direct light and secondary rays in lanes against the
// scalar rules they implement, bit for bit: LocalShading::directLight, and
// the spawn written out below as the specification (mirror reflection,
// Snell refraction, the rays' weights as secondaryRayWeights gives them
// (Whitted's constants, total internal reflection adding the transmitted
// share to the reflected one; Fresnel's for metallic-roughness materials),
// the minimum-weight rule on the weights' largest channel, origins lifted
// off the surface, the ray cone carried on).
#include <gtest/gtest.h>

#include <bit>
#include <optional>
#include <random>
#include <vector>

#include "core/Optics.h"
#include "render/HitLanes.h"
#include "render/LocalShading.h"
#include "render/MetallicRoughness.h"
#include "render/RayCone.h"
#include "render/ScalarShadingRule.h"
#include "render/SecondaryRayWeights.h"
#include "render/SurfaceTextures.h"

using namespace raycache;

namespace {

// `material` with lane k's metallic and roughness as its factors: what the
// scalar shading rules (the specification of the lanes) take for that hit.
Material materialAtLane(const Material& material, const SurfaceLanes16& surfaces, int k) {
    Material atLane = material;
    atLane.metallic = surfaces.metallic[k];
    atLane.roughness = surfaces.roughness[k];
    return atLane;
}


std::uint32_t floatBits(float f) { return std::bit_cast<std::uint32_t>(f); }

Vec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<float> g;
    return normalize(Vec3{g(rng), g(rng), g(rng)});
}

// Sixteen surfaces facing the rays that hit them, some from inside.
struct LaneHits {
    SurfaceLanes16 lanes{};
    RayLanes16 rays{};
    SurfacePoint points[16];
    Ray scalarRays[16];
};

LaneHits randomLaneHits(std::mt19937& rng) {
    std::uniform_real_distribution<float> coord(-50.0f, 50.0f), near(-0.9f, 0.9f), unit(0.0f, 1.0f);
    LaneHits h;
    for (int k = 0; k < 16; ++k) {
        SurfacePoint& sp = h.points[k];
        sp.position = Vec3{coord(rng), coord(rng), coord(rng)} * (k % 4 == 0 ? 0.01f : 1.0f);
        sp.geometricNormal = randomDirection(rng);
        sp.normal = normalize(sp.geometricNormal + Vec3{near(rng), near(rng), near(rng)} * 0.3f);
        sp.frontFace = k % 3 != 0;
        sp.u = unit(rng), sp.v = unit(rng);
        // A ray arriving against the geometric normal, as surfaces are turned.
        Vec3 d = randomDirection(rng);
        if (dot(d, sp.geometricNormal) > 0.0f) d = -d;
        const float t = 0.5f + 20.0f * unit(rng);
        h.scalarRays[k] = Ray{sp.position - d * t, d};
        setLaneRay(h.rays, k, h.scalarRays[k]);
        h.rays.tFar[k] = t;
        SurfaceLanes16& s = h.lanes;
        s.positionX[k] = sp.position.x, s.positionY[k] = sp.position.y, s.positionZ[k] = sp.position.z;
        s.normalX[k] = sp.normal.x, s.normalY[k] = sp.normal.y, s.normalZ[k] = sp.normal.z;
        s.geometricX[k] = sp.geometricNormal.x, s.geometricY[k] = sp.geometricNormal.y;
        s.geometricZ[k] = sp.geometricNormal.z;
        s.u[k] = sp.u, s.v[k] = sp.v;
        s.albedoR[k] = unit(rng), s.albedoG[k] = unit(rng), s.albedoB[k] = unit(rng);
        s.frontFace[k] = sp.frontFace ? 1 : 0;
    }
    return h;
}

// The surfaces' metallic and roughness lanes: the material's factors, or in
// one round of three each lane's own (as a metallic-roughness texture gives
// them: the factors times a value in [0, 1] per lane, or for smooth
// materials a roughness on either side of kSmoothRoughness).
void setMaterialLanes(LaneHits& h, const Material& material, int round, std::mt19937& rng) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const bool textured = round % 3 == 2;
    for (int k = 0; k < 16; ++k) {
        h.lanes.metallic[k] = textured ? material.metallic * unit(rng) : material.metallic;
        h.lanes.roughness[k] = !textured                                  ? material.roughness
                               : material.roughness < kSmoothRoughness ? 2.0f * kSmoothRoughness * unit(rng)
                                                                       : material.roughness * unit(rng);
    }
}

// The rays one hit spawns (the specification secondaryRayLanes16 implements),
// with their weights as secondaryRayWeights gives them.
struct SpawnRuleRays {
    std::optional<Ray> reflected, refracted;
    SecondaryRayWeights weights;
    RayCone cone;
};

SpawnRuleRays spawnRule(const Material& material, float curvature, float minWeight, const SurfacePoint& sp,
                        const Rgb& albedo, const Ray& ray, float t, float pathWeight, const RayCone& cone) {
    SpawnRuleRays out;
    const float offset = surfaceOffset(sp.position);
    out.cone = cone.bounced(t, curvature);
    out.weights = secondaryRayWeights(material, albedo, -dot(ray.direction, sp.normal), sp.frontFace);
    if (material.refracts()) {
        // Entering: air -> material; leaving: material -> air.
        const float eta = sp.frontFace ? 1.0f / material.ior : material.ior;
        const auto direction = refract(ray.direction, sp.normal, eta);
        EXPECT_EQ(direction.has_value(), !out.weights.totalInternal);
        if (direction && pathWeight * out.weights.refracted.maxComponent() >= minWeight)
            out.refracted = Ray{sp.position - sp.geometricNormal * offset, normalize(*direction)};
    }
    const float reflectWeight = out.weights.reflected.maxComponent();
    // An opaque metallic-roughness surface reflects a mirror ray where it is smooth.
    const bool rough = material.model == ShadingModel::MetallicRoughness && !material.refracts() &&
                       !(material.roughness < kSmoothRoughness);
    if (!rough && reflectWeight > 0.0f && pathWeight * reflectWeight >= minWeight)
        out.reflected = Ray{sp.position + sp.geometricNormal * offset, normalize(reflect(ray.direction, sp.normal))};
    return out;
}

void expectSameWeight(const float* r, const float* g, const float* b, int k, const Rgb& expected, const char* what) {
    EXPECT_EQ(floatBits(r[k]), floatBits(expected.r)) << what << " lane " << k;
    EXPECT_EQ(floatBits(g[k]), floatBits(expected.g)) << what << " lane " << k;
    EXPECT_EQ(floatBits(b[k]), floatBits(expected.b)) << what << " lane " << k;
}

void expectSameRay(const float* x, const float* y, const float* z, const float* ox, const float* oy, const float* oz,
                   int k, const Ray& expected, const char* what) {
    EXPECT_EQ(floatBits(x[k]), floatBits(expected.direction.x)) << what << " lane " << k;
    EXPECT_EQ(floatBits(y[k]), floatBits(expected.direction.y)) << what << " lane " << k;
    EXPECT_EQ(floatBits(z[k]), floatBits(expected.direction.z)) << what << " lane " << k;
    EXPECT_EQ(floatBits(ox[k]), floatBits(expected.origin.x)) << what << " lane " << k;
    EXPECT_EQ(floatBits(oy[k]), floatBits(expected.origin.y)) << what << " lane " << k;
    EXPECT_EQ(floatBits(oz[k]), floatBits(expected.origin.z)) << what << " lane " << k;
}

}  // namespace

// directLightLanes16 against LocalShading::directLight for the materials
// `materialOf(round, rng)` gives, under classic and physical lights.
template <typename MaterialOf>
void expectDirectLightEqualsLocalShading(MaterialOf materialOf) {
    Scene scene;
    Light point;
    point.position = {3.0f, 9.0f, -2.0f};
    Light directional;
    directional.type = LightType::Directional;
    directional.direction = normalize(Vec3{0.3f, -1.0f, 0.2f});
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {-4.0f, 6.0f, 1.0f};
    spot.direction = normalize(Vec3{0.5f, -1.0f, 0.0f});
    spot.coneAngleDeg = 40.0f;
    spot.falloffAngleDeg = 15.0f;
    // Physical lights (scene/Light.h): inverse-square falloff, one with a
    // range window that cuts some surfaces off, and glTF's spot cone.
    Light physicalPoint = point;
    physicalPoint.physical = true;
    physicalPoint.position = {-2.0f, 3.0f, 4.0f};
    physicalPoint.range = 60.0f;
    Light physicalSpot = spot;
    physicalSpot.physical = true;
    physicalSpot.intensity = Rgb{40.0f, 30.0f, 20.0f};
    Light physicalSun = directional;
    physicalSun.physical = true;
    scene.lights = {point, directional, spot, physicalPoint, physicalSpot, physicalSun};
    const LocalShading shading(scene);
    std::mt19937 rng(17);
    std::uniform_int_distribution<int> coin(0, 1);
    int lit = 0;
    for (int round = 0; round < 1500; ++round) {
        const Material material = materialOf(round, rng);
        LaneHits h = randomLaneHits(rng);
        setMaterialLanes(h, material, round, rng);
        alignas(64) int selected[16];
        for (int k = 0; k < 16; ++k) selected[k] = k % 5 == 4 ? 0 : -1;
        std::vector<LightLanes16> seen(scene.lights.size());
        for (std::size_t l = 0; l < scene.lights.size(); ++l) {
            RayLanes16 rays;
            PacketLanes traced;
            shadowRayLanes16(scene.lights[l], shading.spotCones()[l], h.lanes, selected, rays, traced, seen[l]);
            for (int k = 0; k < 16; ++k) {
                seen[l].traced[k] = traced.valid[k] ? 1 : 0;
                seen[l].lit[k] = traced.valid[k] && coin(rng) ? 1 : 0;  // some blocked
            }
        }
        alignas(64) float r[16], g[16], b[16];
        for (int k = 0; k < 16; ++k) r[k] = g[k] = b[k] = -1.0f;
        directLightLanes16(material, scene.lights, seen.data(), h.lanes, h.rays, selected, r, g, b);
        // The Render Cache's parts of it: the light that does not depend on
        // the eye (with the albedo and with a white one) and the highlights.
        alignas(64) float viewR[16], viewG[16], viewB[16], whiteR[16], whiteG[16], whiteB[16];
        alignas(64) float highR[16], highG[16], highB[16];
        viewIndependentLightLanes16(material, scene.lights, seen.data(), h.lanes, false, selected, viewR, viewG,
                                    viewB);
        viewIndependentLightLanes16(material, scene.lights, seen.data(), h.lanes, true, selected, whiteR, whiteG,
                                    whiteB);
        highlightLanes16(material, scene.lights, seen.data(), h.lanes, h.rays, selected, highR, highG, highB);
        for (int k = 0; k < 16; ++k) {
            if (!selected[k]) {
                EXPECT_EQ(r[k], -1.0f) << "a lane left out is written, lane " << k;
                continue;
            }
            ShadowQuery queries[kMaxLights];
            unsigned char occluded[kMaxLights];
            const int n = shading.shadowQueries(h.points[k], queries);
            for (int q = 0; q < n; ++q) {
                occluded[q] = seen[static_cast<std::size_t>(queries[q].lightIndex)].lit[k] ? 0 : 1;
                lit += occluded[q] ? 0 : 1;
            }
            const Rgb albedo{h.lanes.albedoR[k], h.lanes.albedoG[k], h.lanes.albedoB[k]};
            const Rgb expected = scalarDirectLight(shading, materialAtLane(material, h.lanes, k), albedo, h.points[k],
                                                     -h.scalarRays[k].direction,
                                                     std::span(queries, static_cast<std::size_t>(n)),
                                                     std::span(occluded, static_cast<std::size_t>(n)));
            EXPECT_EQ(floatBits(r[k]), floatBits(expected.r)) << "lane " << k;
            EXPECT_EQ(floatBits(g[k]), floatBits(expected.g)) << "lane " << k;
            EXPECT_EQ(floatBits(b[k]), floatBits(expected.b)) << "lane " << k;
            const Material atLane = materialAtLane(material, h.lanes, k);
            const std::span<const ShadowQuery> seenQueries(queries, static_cast<std::size_t>(n));
            const std::span<const unsigned char> blocked(occluded, static_cast<std::size_t>(n));
            std::uint64_t litMask = 0, whiteLitMask = 0;
            const Rgb viewIndependent = scalarViewIndependentLight(shading, atLane, albedo, h.points[k], seenQueries,
                                                                     blocked, litMask);
            const Rgb white = scalarViewIndependentLight(shading, atLane, Rgb{1.0f}, h.points[k], seenQueries, blocked,
                                                           whiteLitMask);
            expectSameWeight(viewR, viewG, viewB, k, viewIndependent, "view-independent light");
            expectSameWeight(whiteR, whiteG, whiteB, k, white, "view-independent light, white albedo");
            std::uint64_t laneLitMask = 0;
            for (std::size_t l = 0; l < scene.lights.size(); ++l)
                if (seen[l].lit[k]) laneLitMask |= std::uint64_t{1} << l;
            EXPECT_EQ(laneLitMask, litMask) << "lane " << k;
            const Rgb highlights =
                scalarHighlights(shading, atLane, albedo, h.points[k], -h.scalarRays[k].direction, seenQueries, litMask);
            expectSameWeight(highR, highG, highB, k, highlights, "highlights");
        }
        if (::testing::Test::HasFailure()) return;
    }
    EXPECT_GT(lit, 1500 * 4);  // lights do reach surfaces: not a vacuous comparison
}

TEST(ShadingLanes, DirectLightEqualsLocalShading) {
    expectDirectLightEqualsLocalShading([](int round, std::mt19937&) {
        Material material;
        material.diffuse = Rgb{0.7f, 0.4f, 0.2f};
        material.ambient = Rgb{0.05f, 0.1f, 0.02f};
        material.specular = Rgb{0.3f, 0.5f, 0.9f};
        material.shininess = round % 3 == 0 ? 7.5f : static_cast<float>(1 + round % 64);  // whole and not
        return material;
    });
}

// glTF's BRDF, every roughness (smooth ones without the lobe) and metallic.
TEST(ShadingLanes, MetallicRoughnessEqualsLocalShading) {
    expectDirectLightEqualsLocalShading([](int round, std::mt19937& rng) {
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        Material material;
        material.model = ShadingModel::MetallicRoughness;
        material.ambient = Rgb(0.0f);
        material.metallic = round % 4 == 0 ? 1.0f : (round % 4 == 1 ? 0.0f : unit(rng));
        material.roughness = round % 5 == 0 ? 0.05f * unit(rng) : (round % 5 == 1 ? 1.0f : unit(rng));
        material.emission = round % 3 == 0 ? Rgb{0.2f, 0.0f, 0.7f} : Rgb(0.0f);
        // KHR_materials_specular's F0 and F90 in one round of seven.
        if (round % 7 == 0) {
            material.specularF0 = {0.08f * unit(rng), 0.08f * unit(rng), 0.0f};
            material.specularF90 = unit(rng);
        }
        return material;
    });
}

// secondaryRayLanes16 against the spawn rule above for the materials
// `materialOf(round, rng)` gives; counts how often each branch was taken.
struct SpawnCounts {
    int reflected = 0, refracted = 0, totalInternal = 0, belowMinWeight = 0, tinted = 0;
    int roughLanes = 0;  // opaque metallic-roughness lanes too rough for a mirror ray
};

template <typename MaterialOf>
SpawnCounts expectSecondaryRaysEqualSpawnRule(MaterialOf materialOf) {
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    SpawnCounts counts;
    for (int round = 0; round < 3000; ++round) {
        const Material material = materialOf(round, rng);
        const float curvature = round % 3 == 0 ? 0.0f : 1.0f / (0.1f + 5.0f * unit(rng));
        const float minWeight = round % 4 == 0 ? 0.3f : 0.001f;
        LaneHits h = randomLaneHits(rng);
        setMaterialLanes(h, material, round, rng);
        alignas(64) float pathWeight[16], coneWidth[16], coneSpread[16];
        alignas(64) int selected[16];
        for (int k = 0; k < 16; ++k) {
            pathWeight[k] = unit(rng);
            coneWidth[k] = unit(rng) * 0.01f;
            coneSpread[k] = unit(rng) * 0.002f;
            selected[k] = k % 6 == 5 ? 0 : -1;
        }
        SecondaryRayLanes16 out{};
        secondaryRayLanes16(material, curvature, minWeight, h.lanes, h.rays, pathWeight, coneWidth, coneSpread,
                            selected, out);
        for (int k = 0; k < 16; ++k) {
            if (!selected[k]) {
                EXPECT_EQ(out.reflects[k], 0) << "a lane left out spawns, lane " << k;
                EXPECT_EQ(out.refracts[k], 0) << "a lane left out spawns, lane " << k;
                continue;
            }
            const Rgb albedo{h.lanes.albedoR[k], h.lanes.albedoG[k], h.lanes.albedoB[k]};
            const SpawnRuleRays expected =
                spawnRule(materialAtLane(material, h.lanes, k), curvature, minWeight, h.points[k], albedo,
                          h.scalarRays[k], h.rays.tFar[k], pathWeight[k], {coneWidth[k], coneSpread[k]});
            if (material.model == ShadingModel::MetallicRoughness && !material.refracts() &&
                !(h.lanes.roughness[k] < kSmoothRoughness))
                ++counts.roughLanes;
            EXPECT_EQ(floatBits(out.coneWidth[k]), floatBits(expected.cone.width)) << "lane " << k;
            EXPECT_EQ(floatBits(out.coneSpread[k]), floatBits(expected.cone.spread)) << "lane " << k;
            EXPECT_EQ(out.reflects[k] != 0, expected.reflected.has_value()) << "round " << round << " lane " << k;
            EXPECT_EQ(out.refracts[k] != 0, expected.refracted.has_value()) << "round " << round << " lane " << k;
            if (::testing::Test::HasFailure()) return counts;
            if (expected.reflected) {
                ++counts.reflected;
                expectSameWeight(out.reflectR, out.reflectG, out.reflectB, k, expected.weights.reflected, "reflected");
                expectSameRay(out.reflectedX, out.reflectedY, out.reflectedZ, out.aboveX, out.aboveY, out.aboveZ, k,
                              *expected.reflected, "reflected");
                const Rgb& w = expected.weights.reflected;
                if (w.r != w.g || w.g != w.b) ++counts.tinted;
            }
            if (expected.refracted) {
                ++counts.refracted;
                expectSameWeight(out.refractR, out.refractG, out.refractB, k, expected.weights.refracted, "refracted");
                expectSameRay(out.refractedX, out.refractedY, out.refractedZ, out.belowX, out.belowY, out.belowZ, k,
                              *expected.refracted, "refracted");
            }
            if (material.refracts() && expected.weights.totalInternal) ++counts.totalInternal;
            if (material.refracts() && !expected.refracted && !expected.weights.totalInternal) ++counts.belowMinWeight;
        }
        if (::testing::Test::HasFailure()) return counts;
    }
    return counts;
}

TEST(ShadingLanes, SecondaryRaysEqualWhittedsSpawn) {
    const SpawnCounts counts = expectSecondaryRaysEqualSpawnRule([](int round, std::mt19937& rng) {
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        Material material;
        material.reflectivity = round % 7 == 0 ? 0.0f : unit(rng);
        material.transmissivity = round % 2 == 0 ? unit(rng) : 0.0f;
        material.ior = 1.0f + unit(rng);
        return material;
    });
    // Every branch of the rule was taken.
    EXPECT_GT(counts.reflected, 1000);
    EXPECT_GT(counts.refracted, 1000);
    EXPECT_GT(counts.totalInternal, 100);
    EXPECT_GT(counts.belowMinWeight, 100);
}

// Metallic-roughness mirrors (Schlick's Fresnel, tinted by the albedo for
// metals) and glass (the exact dielectric Fresnel, a tinted transmission).
TEST(ShadingLanes, MetallicRoughnessSecondaryRaysEqualFresnelWeights) {
    const SpawnCounts counts = expectSecondaryRaysEqualSpawnRule([](int round, std::mt19937& rng) {
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        Material material;
        material.model = ShadingModel::MetallicRoughness;
        material.metallic = round % 4 == 0 ? 1.0f : (round % 4 == 1 ? 0.0f : unit(rng));
        material.roughness = 0.05f * unit(rng);
        material.reflectivity = 1.0f;
        if (round % 7 == 3) {
            material.specularF0 = {0.08f * unit(rng), 0.0f, 0.08f * unit(rng)};
            material.specularF90 = unit(rng);
        }
        if (round % 2 == 0) {
            material.metallic = round % 8 == 0 ? 0.0f : material.metallic;
            material.transmissivity = round % 6 == 0 ? 1.0f : unit(rng);
            material.ior = round % 10 == 0 ? 1.0f : 1.0f + unit(rng);
            material.transmissionTint = round % 3 == 0 ? Rgb(1.0f) : Rgb{unit(rng), unit(rng), unit(rng)};
        }
        return material;
    });
    EXPECT_GT(counts.reflected, 1000);
    EXPECT_GT(counts.refracted, 1000);
    EXPECT_GT(counts.totalInternal, 100);
    EXPECT_GT(counts.belowMinWeight, 100);
    EXPECT_GT(counts.tinted, 1000);  // metals' weights differ per channel
    EXPECT_GT(counts.roughLanes, 1000);  // a texture's rough lanes spawn no mirror ray
}
