// glTF's metallic-roughness BRDF (render/MetallicRoughness.h) and physical
// lights (scene/Light.h) against values worked out independently here:
// Schlick's weight at known angles, the GGX lobe's directional albedo
// integrated numerically, and KHR_lights_punctual's spot cone and falloff.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/LocalShading.h"
#include "render/MetallicRoughness.h"

using namespace raycache;

namespace {

// The energy the specular lobe reflects toward a viewer at cosine `cosV`:
// the integral of D * Vis * F * cos(l) over the hemisphere, by GGX's own
// distribution of half vectors (stratified, deterministic): tan^2(theta_h)
// = alpha^2 s / (1 - s), the pdf of l being D cos(h) / (4 (v.h)).
double specularAlbedo(const Material& m, const Rgb& baseColor, double cosV) {
    const double alpha = static_cast<double>(m.roughness) * m.roughness;
    const Vec3 n{0.0f, 0.0f, 1.0f};
    const Vec3 v{static_cast<float>(std::sqrt(1.0 - cosV * cosV)), 0.0f, static_cast<float>(cosV)};
    constexpr int kS = 2000, kPhi = 400;
    double sum = 0.0;
    for (int i = 0; i < kS; ++i) {
        const double s = (i + 0.5) / kS;
        const double tanH = alpha * std::sqrt(s / (1.0 - s));
        const double cosH = 1.0 / std::sqrt(1.0 + tanH * tanH), sinH = tanH * cosH;
        for (int j = 0; j < kPhi; ++j) {
            const double phi = 2.0 * std::numbers::pi * (j + 0.5) / kPhi;
            const double hx = sinH * std::cos(phi), hy = sinH * std::sin(phi), hz = cosH;
            const double vDotH = v.x * hx + v.y * hy + v.z * hz;
            if (vDotH <= 0.0) continue;
            const Vec3 l{static_cast<float>(2.0 * vDotH * hx - v.x), static_cast<float>(2.0 * vDotH * hy - v.y),
                         static_cast<float>(2.0 * vDotH * hz - v.z)};
            if (l.z <= 0.0f) continue;
            const double a2 = alpha * alpha;
            const double d = cosH * cosH * (a2 - 1.0) + 1.0;
            const double distribution = a2 / (std::numbers::pi * d * d);
            const double pdf = distribution * cosH / (4.0 * vDotH);
            const Rgb f = ggxSpecular(m, baseColor, n, normalize(l), v);
            sum += f.r * l.z / pdf;
        }
    }
    return sum / (static_cast<double>(kS) * kPhi);
}

Material metal(float roughness) {
    Material m;
    m.model = ShadingModel::MetallicRoughness;
    m.metallic = 1.0f;
    m.roughness = roughness;
    return m;
}

}  // namespace

TEST(MetallicRoughness, SchlickWeightAtKnownAngles) {
    EXPECT_FLOAT_EQ(schlickWeight(1.0f), 0.0f);                   // normal incidence: F = F0
    EXPECT_FLOAT_EQ(schlickWeight(0.5f), 0.03125f);               // 60 degrees: 0.5^5
    EXPECT_FLOAT_EQ(schlickWeight(0.0f), 1.0f);                   // grazing: F = 1
    EXPECT_NEAR(schlickWeight(std::cos(1.2f)), std::pow(1.0 - std::cos(1.2), 5.0), 1e-6);
    EXPECT_FLOAT_EQ(reflectanceAtNormal(0.04f, 0.7f, 0.0f), 0.04f);  // dielectrics: their F0
    EXPECT_FLOAT_EQ(reflectanceAtNormal(0.04f, 0.7f, 1.0f), 0.7f);   // metals: the base colour
}

// A white metal (F0 = 1) reflects at most what arrives: the lobe's
// directional albedo is at most 1 (height-correlated Smith loses the
// energy of multiple scattering, more at higher roughness).
TEST(MetallicRoughness, DirectionalAlbedoAtMostOne) {
    for (float roughness : {1.0f, 0.5f})
        for (double cosV : {1.0, 0.7, 0.3}) {
            const double albedo = specularAlbedo(metal(roughness), Rgb(1.0f), cosV);
            EXPECT_LE(albedo, 1.0) << "roughness " << roughness << " cos " << cosV;
            EXPECT_GT(albedo, roughness < 1.0f ? 0.8 : 0.25) << "roughness " << roughness << " cos " << cosV;
        }
}

// At roughness 1 (D = 1 / pi, Vis = 0.5 / (nl + nv)) seen from above, the
// integral is that of nl / (nl + 1) over [0, 1]: 1 - ln 2.
TEST(MetallicRoughness, DirectionalAlbedoAtRoughnessOneIsOneMinusLnTwo) {
    EXPECT_NEAR(specularAlbedo(metal(1.0f), Rgb(1.0f), 1.0), 1.0 - std::log(2.0), 1e-3);
}

// Near roughness 0 the lobe is a mirror: it reflects Schlick's F at the
// viewer's angle (a dielectric: 0.04 + 0.96 (1 - cos)^5).
TEST(MetallicRoughness, NearlySmoothLobeReflectsFresnel) {
    Material dielectric = metal(0.12f);
    dielectric.metallic = 0.0f;
    for (double cosV : {1.0, 0.7, 0.4}) {
        const double fresnel = 0.04 + 0.96 * std::pow(1.0 - cosV, 5.0);
        EXPECT_NEAR(specularAlbedo(dielectric, Rgb(1.0f), cosV), fresnel, 0.03 * fresnel) << "cos " << cosV;
    }
    EXPECT_NEAR(specularAlbedo(metal(0.12f), Rgb(1.0f), 0.9), 1.0, 0.03);
}

// KHR_lights_punctual: E = I / d^2 windowed by clamp(1 - (d / range)^4, 0, 1);
// a spot's factor ((cos - cos outer) / (cos inner - cos outer))^2 between its cones.
TEST(PhysicalLights, FalloffAndSpotConeAsTheExtensionDefines) {
    Scene scene;
    Light spot;
    spot.type = LightType::Spot;
    spot.physical = true;
    spot.position = {0.0f, 4.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    const double inner = 20.0, outer = 40.0;  // degrees
    spot.coneAngleDeg = static_cast<float>(outer);
    spot.falloffAngleDeg = static_cast<float>(outer - inner);
    Light ranged;
    ranged.physical = true;
    ranged.position = {0.0f, 4.0f, 0.0f};
    ranged.range = 6.0f;
    scene.lights = {spot, ranged};
    const LocalShading shading(scene);
    const double degrees = std::numbers::pi / 180.0;
    for (double angle : {0.0, 10.0, 25.0, 30.0, 35.0, 39.0, 45.0, 60.0}) {
        SurfacePoint sp;
        const double x = 4.0 * std::tan(angle * degrees);
        sp.position = {static_cast<float>(x), 0.0f, 0.0f};
        sp.normal = sp.geometricNormal = {0.0f, 1.0f, 0.0f};
        ShadowQuery queries[kMaxLights];
        const int count = shading.shadowQueries(sp, queries);
        const double d2 = 16.0 + x * x, d = std::sqrt(d2);
        double cone = (std::cos(angle * degrees) - std::cos(outer * degrees)) /
                      (std::cos(inner * degrees) - std::cos(outer * degrees));
        cone = std::clamp(cone, 0.0, 1.0);
        const double spotExpected = cone * cone / d2;
        const double window = std::clamp(1.0 - std::pow(d / 6.0, 4.0), 0.0, 1.0);
        const double rangedExpected = window / d2;
        double spotSeen = 0.0, rangedSeen = 0.0;
        for (int q = 0; q < count; ++q) (queries[q].lightIndex == 0 ? spotSeen : rangedSeen) = queries[q].strength;
        EXPECT_NEAR(spotSeen, spotExpected, 1e-5 + 1e-4 * spotExpected) << angle << " degrees";
        EXPECT_NEAR(rangedSeen, rangedExpected, 1e-5 + 1e-4 * rangedExpected) << angle << " degrees";
    }
}
