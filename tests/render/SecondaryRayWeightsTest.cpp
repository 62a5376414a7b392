// The secondary rays' weights (tests/render/SecondaryRayWeights.h) against values
// worked out independently: the dielectric Fresnel equations in their angle
// form (Fresnel's sines and tangents, in double) and their closed forms at
// normal incidence, Brewster's angle and the critical angle; Schlick's
// Fresnel for metallic-roughness mirrors; and renders of a gold mirror
// sphere and a glass pane in a coloured environment, pixel by pixel, with
// and without a caching cube.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "cache/RayCache.h"
#include "core/Optics.h"
#include "render/SecondaryRayWeights.h"
#include "AnalyticScene.h"

using namespace raycache;

namespace {

constexpr double kPi = std::numbers::pi;

// Fresnel's equations in angle form (Born & Wolf): rs = -sin(θi - θt) /
// sin(θi + θt), rp = tan(θi - θt) / tan(θi + θt), θt by Snell's law
// n1 sin θi = n2 sin θt; squared. Normal incidence has its own limit.
struct AngleFresnel {
    double s, p;
};
AngleFresnel angleFresnel(double thetaI, double n1, double n2) {
    const double thetaT = std::asin(n1 / n2 * std::sin(thetaI));
    const double rs = -std::sin(thetaI - thetaT) / std::sin(thetaI + thetaT);
    const double rp = std::tan(thetaI - thetaT) / std::tan(thetaI + thetaT);
    return {rs * rs, rp * rp};
}

Material glass(float ior, float transmission = 1.0f, Rgb tint = Rgb(1.0f)) {
    Material m;
    m.model = ShadingModel::MetallicRoughness;
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    m.reflectivity = 1.0f;
    m.transmissivity = transmission;
    m.ior = ior;
    m.transmissionTint = tint;
    return m;
}

Material metalMirror(const Rgb& baseColor, float metallic = 1.0f) {
    Material m;
    m.model = ShadingModel::MetallicRoughness;
    m.ambient = Rgb(0.0f);
    m.metallic = metallic;
    m.roughness = 0.0f;
    m.diffuse = baseColor;
    m.reflectivity = 1.0f;
    return m;
}

// The weights at angle `theta` (radians) from the normal, from outside or inside.
SecondaryRayWeights weightsAt(const Material& m, double theta, bool frontFace, const Rgb& albedo = Rgb(1.0f)) {
    return secondaryRayWeights(m, albedo, static_cast<float>(std::cos(theta)), frontFace);
}

}  // namespace

TEST(SecondaryRayWeights, NormalIncidenceIsTheSquaredIorRatioBothWays) {
    for (const float ior : {1.33f, 1.5f, 2.4f}) {
        const double n = ior;
        const double expected = ((n - 1.0) / (n + 1.0)) * ((n - 1.0) / (n + 1.0));
        for (const bool entering : {true, false}) {
            const SecondaryRayWeights w = weightsAt(glass(ior), 0.0, entering);
            EXPECT_NEAR(w.reflected.r, expected, 1e-6) << "ior " << ior << (entering ? " entering" : " leaving");
            EXPECT_NEAR(w.refracted.g, 1.0 - expected, 1e-6);
            EXPECT_FALSE(w.totalInternal);
        }
    }
}

TEST(SecondaryRayWeights, DielectricFresnelMatchesTheAngleFormEnteringAndLeaving) {
    const double n = 1.5;
    const double critical = std::asin(1.0 / n);
    int checked = 0;
    for (int i = 1; i < 90; ++i) {
        const double theta = i * kPi / 180.0;
        // Entering from air.
        const AngleFresnel in = angleFresnel(theta, 1.0, n);
        const double cosT = std::cos(std::asin(std::sin(theta) / n));
        const FresnelReflectance f = dielectricFresnel(static_cast<float>(std::cos(theta)), static_cast<float>(cosT),
                                                       static_cast<float>(1.0 / n));
        EXPECT_NEAR(f.s, in.s, 2e-6) << i << " degrees entering";
        EXPECT_NEAR(f.p, in.p, 2e-6) << i << " degrees entering";
        EXPECT_NEAR(weightsAt(glass(1.5f), theta, true).reflected.g, 0.5 * (in.s + in.p), 2e-6) << i << " degrees";
        ++checked;
        // Leaving the glass, below the critical angle.
        if (theta < critical - 1e-3) {
            const AngleFresnel out = angleFresnel(theta, n, 1.0);
            const SecondaryRayWeights w = weightsAt(glass(1.5f), theta, false);
            EXPECT_FALSE(w.totalInternal) << i << " degrees leaving";
            EXPECT_NEAR(w.reflected.b, 0.5 * (out.s + out.p), 2e-5) << i << " degrees leaving";
            EXPECT_NEAR(w.refracted.r, 1.0 - 0.5 * (out.s + out.p), 2e-5) << i << " degrees leaving";
            ++checked;
        }
    }
    EXPECT_EQ(checked, 89 + 41);
}

TEST(SecondaryRayWeights, BrewsterAngleReflectsNoParallelLight) {
    // At θB = atan(n2 / n1) the p reflectance vanishes and the s one is
    // ((n2² - n1²) / (n2² + n1²))², from either side.
    for (const double ratio : {1.5, 1.0 / 1.5}) {
        const double thetaB = std::atan(ratio);
        const double thetaT = kPi / 2.0 - thetaB;  // reflected and refracted rays at right angles
        const FresnelReflectance f = dielectricFresnel(static_cast<float>(std::cos(thetaB)),
                                                       static_cast<float>(std::cos(thetaT)),
                                                       static_cast<float>(1.0 / ratio));
        const double rs = (ratio * ratio - 1.0) / (ratio * ratio + 1.0);
        EXPECT_NEAR(f.p, 0.0, 1e-7) << "n2/n1 " << ratio;
        EXPECT_NEAR(f.s, rs * rs, 1e-6) << "n2/n1 " << ratio;
        const Material m = glass(1.5f);
        EXPECT_NEAR(weightsAt(m, thetaB, ratio > 1.0).reflected.r, 0.5 * rs * rs, 1e-6) << "n2/n1 " << ratio;
    }
}

TEST(SecondaryRayWeights, BeyondTheCriticalAngleEverythingIsReflected) {
    const float ior = 1.5f;
    const double critical = std::asin(1.0 / ior);
    const Material m = glass(ior, 0.7f, Rgb{0.9f, 0.5f, 0.2f});
    for (const double offset : {1e-3, 0.1, 0.5}) {
        const SecondaryRayWeights beyond = weightsAt(m, critical + offset, false);
        EXPECT_TRUE(beyond.totalInternal);
        EXPECT_EQ(beyond.reflected, Rgb(1.0f));
        EXPECT_EQ(beyond.refracted, Rgb(0.0f));
        const SecondaryRayWeights before = weightsAt(m, critical - offset, false);
        EXPECT_FALSE(before.totalInternal);
        EXPECT_LT(before.reflected.r, 1.0f);
        // What is not reflected is refracted, times the transmission and its tint.
        EXPECT_NEAR(before.refracted.r, (1.0f - before.reflected.r) * 0.7f * 0.9f, 1e-6);
        EXPECT_NEAR(before.refracted.b, (1.0f - before.reflected.r) * 0.7f * 0.2f, 1e-6);
        // Entering at the same angle never reflects everything.
        EXPECT_FALSE(weightsAt(m, critical + offset, true).totalInternal);
    }
    // Just below the critical angle the reflectance rises steeply toward 1.
    EXPECT_GT(weightsAt(m, critical - 1e-4, false).reflected.r, 0.9f);
}

TEST(SecondaryRayWeights, EnteringAndLeavingAlongOnePathReflectAlike) {
    // Light crossing the boundary at θi outside and θt inside meets the same
    // reflectance from either side (Stokes' relations).
    for (int i = 0; i < 90; i += 5) {
        const double thetaI = i * kPi / 180.0;
        const double thetaT = std::asin(std::sin(thetaI) / 1.5);
        const float in = weightsAt(glass(1.5f), thetaI, true).reflected.r;
        const float out = weightsAt(glass(1.5f), thetaT, false).reflected.r;
        EXPECT_NEAR(in, out, 2e-6 + 1e-4 * in) << i << " degrees";
    }
}

TEST(SecondaryRayWeights, SmoothSurfacesReflectSchlicksFresnelTintedByAMetal) {
    const Rgb gold{1.0f, 0.77f, 0.34f};
    for (int i = 0; i <= 90; i += 10) {
        const double theta = i * kPi / 180.0;
        const double w = std::pow(1.0 - std::cos(theta), 5.0);
        const SecondaryRayWeights metal = weightsAt(metalMirror(gold), theta, true, gold);
        EXPECT_NEAR(metal.reflected.r, 1.0, 1e-6) << i;
        EXPECT_NEAR(metal.reflected.g, 0.77 + 0.23 * w, 1e-6) << i;
        EXPECT_NEAR(metal.reflected.b, 0.34 + 0.66 * w, 1e-6) << i;
        EXPECT_EQ(metal.refracted, Rgb(0.0f));
        // A dielectric reflects 0.04 at normal incidence whatever its colour.
        const SecondaryRayWeights plastic = weightsAt(metalMirror(gold, 0.0f), theta, true, gold);
        EXPECT_NEAR(plastic.reflected.b, 0.04 + 0.96 * w, 1e-6) << i;
        EXPECT_EQ(plastic.reflected.r, plastic.reflected.b);
    }
}

TEST(SecondaryRayWeights, BlinnPhongKeepsWhittedsConstants) {
    Material m;
    m.reflectivity = 0.3f;
    m.transmissivity = 0.6f;
    m.ior = 1.5f;
    const SecondaryRayWeights in = weightsAt(m, 0.7, true);
    EXPECT_EQ(in.reflected, Rgb(0.3f));
    EXPECT_EQ(in.refracted, Rgb(0.6f));
    const SecondaryRayWeights trapped = weightsAt(m, 1.2, false);  // beyond 41.8 degrees inside
    EXPECT_TRUE(trapped.totalInternal);
    EXPECT_EQ(trapped.reflected, Rgb(0.3f + 0.6f));
}

namespace {

// Six distinct colours, one per cube face (+x, -x, +y, -y, +z, -z).
const std::array<Rgb, 6> kFaceColors{Rgb{1, 0, 0}, Rgb{0, 1, 0}, Rgb{0, 0, 1},
                                     Rgb{1, 1, 0}, Rgb{0, 1, 1}, Rgb{1, 0, 1}};

Environment colouredCube() {
    std::array<std::shared_ptr<const Image>, 6> faces;
    for (std::size_t f = 0; f < 6; ++f) {
        auto image = std::make_shared<Image>(1, 1);
        image->at(0, 0) = kFaceColors[f];
        faces[f] = image;
    }
    return Environment::cubeFaces(faces);
}

// The face colour along `d`, or nothing near a cube edge (where float
// rounding, or a cube texel's ray, may see the neighbour).
std::optional<Rgb> faceColor(analytic::DVec d) {
    const double ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    const double major = std::max({ax, ay, az});
    const double second = ax + ay + az - major - std::min({ax, ay, az});
    if (major - second < 0.02 * major) return std::nullopt;
    const int axis = major == ax ? 0 : (major == ay ? 1 : 2);
    const double component = axis == 0 ? d.x : (axis == 1 ? d.y : d.z);
    return kFaceColors[static_cast<std::size_t>(2 * axis + (component < 0 ? 1 : 0))];
}

void expectNear(const Rgb& got, double r, double g, double b, double tolerance, int x, int y) {
    EXPECT_NEAR(got.r, r, tolerance) << x << "," << y;
    EXPECT_NEAR(got.g, g, tolerance) << x << "," << y;
    EXPECT_NEAR(got.b, b, tolerance) << x << "," << y;
}

}  // namespace

// A gold mirror ball (metallic 1, roughness 0) in the coloured cube: each
// pixel is the face seen along the reflected ray times Schlick's Fresnel of
// gold at that pixel's angle, channel by channel; and the same again when a
// caching cube answers the second frame (the cube holds what the ray brings
// back, unweighted; a cube that stored it weighted would show gold twice).
TEST(SecondaryRayWeights, GoldMirrorReflectsTintedByItsBaseColour) {
    const Rgb gold{1.0f, 0.77f, 0.34f};
    Material m = metalMirror(gold);
    m.cache.technique = CacheTechnique::Cct;
    m.cache.faceResolution = 64;
    Scene scene;
    scene.objects.push_back(SceneObject{"ball", Sphere{{0, 0, 0}, 1.0f}, m, {0, 0, 0}});
    scene.camera = analytic::analyticCamera();
    scene.environment = colouredCube();
    RenderSettings settings;
    settings.width = settings.height = analytic::kSize;
    const TraceScene tracer(scene);
    const Parallel parallel(2);
    RayCache cache(scene, settings.cache);
    const FrameRenderer renderer(scene, tracer, settings, parallel, &cache);
    for (int frame = 0; frame < 2; ++frame) {
        Image image;
        const FrameStats stats = renderer.render(scene.camera, image);
        ASSERT_TRUE(stats.cache);
        if (frame == 1) {
            EXPECT_GT(stats.cache->hits(), 500u);
        }
        int checked = 0, tinted = 0;
        for (int y = 0; y < analytic::kSize; ++y)
            for (int x = 0; x < analytic::kSize; ++x) {
                const analytic::DVec d = analytic::pixelDirection(x, y);
                const analytic::SphereHit hit = analytic::raySphere(analytic::kEye, d, {0, 0, 0}, 1.0);
                if (hit.disc < 0.05) continue;  // off the ball, or near its silhouette
                const analytic::DVec n = analytic::kEye + d * hit.tNear;
                const double cosine = -dot(d, n);
                const std::optional<Rgb> seen = faceColor(d - n * (2.0 * dot(d, n)));
                if (!seen) continue;
                const double w = std::pow(1.0 - cosine, 5.0);
                const double fr = 1.0, fg = 0.77 + 0.23 * w, fb = 0.34 + 0.66 * w;
                expectNear(image.at(x, y), seen->r * fr, seen->g * fg, seen->b * fb, 1e-4, x, y);
                if (seen->g > 0.0f && seen->b > 0.0f && image.at(x, y).b < 0.5f * image.at(x, y).g) ++tinted;
                ++checked;
            }
        EXPECT_GT(checked, 500) << "frame " << frame;
        EXPECT_GT(tinted, 50) << "frame " << frame;  // gold, not grey: blue well below green
        if (HasFailure()) return;
    }
}

// A glass pane tilted from the view, seen from the front (entering, 60
// degrees at the centre) and from behind (leaving, 38 degrees at the
// centre, the top of the view within the critical angle and the bottom
// beyond it): F times the face along the reflected ray plus (1 - F) times
// the tint times the face along the refracted ray, F the exact Fresnel
// worked out here in angle form.
TEST(SecondaryRayWeights, GlassPaneShowsFresnelsShareOfEachSide) {
    const Rgb tint{0.9f, 0.6f, 0.3f};
    for (const bool fromBehind : {false, true}) {
        // The normal the camera's rays meet, tilted by alpha from +z toward -y.
        const double alpha = (fromBehind ? 38.0 : 60.0) * kPi / 180.0;
        const analytic::DVec n{0.0, -std::sin(alpha), std::cos(alpha)};
        // makePlane() lies in xz with normal +y; a turn of phi about x makes
        // its normal (0, cos phi, sin phi): n, or -n to be seen from behind.
        const double phiDegrees = 90.0 + alpha * 180.0 / kPi + (fromBehind ? 180.0 : 0.0);
        const Transform t =
            Transform::rotate({1, 0, 0}, static_cast<float>(phiDegrees)) * Transform::scale({20, 1, 20});
        Scene scene;
        scene.objects.push_back(SceneObject{
            "pane", MeshShape{std::make_shared<const TriangleMesh>(transformed(makePlane(), t))},
            glass(1.5f, 1.0f, tint), {0, 0, 0}});
        scene.camera = analytic::analyticCamera();
        scene.environment = colouredCube();
        const Image image = analytic::renderAnalytic(scene);
        const double n1 = fromBehind ? 1.5 : 1.0, n2 = fromBehind ? 1.0 : 1.5;
        int refracted = 0, totalInternal = 0;
        for (int y = 0; y < analytic::kSize; ++y)
            for (int x = 0; x < analytic::kSize; ++x) {
                const analytic::DVec d = analytic::pixelDirection(x, y);
                const double cosI = -dot(d, n);
                // The hit must lie on the pane (a 20 x 20 square about the origin).
                const analytic::DVec p = analytic::kEye + d * (dot(analytic::kEye, n) / cosI);
                if (cosI <= 0.0 || length(p) > 9.0) continue;
                const std::optional<Rgb> mirrored = faceColor(d + n * (2.0 * cosI));
                if (!mirrored) continue;
                const double thetaI = std::acos(cosI);
                const double sinT = n1 / n2 * std::sin(thetaI);
                if (std::fabs(sinT - 1.0) < 1e-3) continue;  // at the critical angle F is steep
                if (sinT > 1.0) {
                    expectNear(image.at(x, y), mirrored->r, mirrored->g, mirrored->b, 1e-4, x, y);
                    ++totalInternal;
                    continue;
                }
                const double cosT = std::sqrt(1.0 - sinT * sinT);
                const double eta = n1 / n2;
                const std::optional<Rgb> through = faceColor(d * eta + n * (eta * cosI - cosT));
                if (!through) continue;
                const AngleFresnel f = angleFresnel(thetaI, n1, n2);
                const double fresnel = 0.5 * (f.s + f.p);
                const double rest = 1.0 - fresnel;
                expectNear(image.at(x, y), fresnel * mirrored->r + rest * tint.r * through->r,
                           fresnel * mirrored->g + rest * tint.g * through->g,
                           fresnel * mirrored->b + rest * tint.b * through->b, 2e-4, x, y);
                ++refracted;
                if (HasFailure()) return;
            }
        EXPECT_GT(refracted, 300) << (fromBehind ? "from behind" : "from the front");
        if (fromBehind) {
            EXPECT_GT(totalInternal, 300);
        }
    }
}
