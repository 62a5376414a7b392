// Full renders of a wall lit by one light, checked pixel by pixel against the
// lighting model docs/architecture.md states (Whitted with Blinn-Phong, lights
// without distance falloff, spot lights fading by smoothstep between
// cone - falloff and cone), evaluated here in double precision: the highlight
// and its peak, a point light, a spot light's cone, and the exact shadow of a
// sphere. The model is reimplemented from its description, not from the code.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "AnalyticScene.h"

using namespace raycache;
using namespace raycache::analytic;

namespace {

constexpr double kTolerance = 1e-3;
const DVec kWallNormal{0, 0, 1};

double smoothstepD(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}
double cosDeg(double degrees) {
    return std::cos(degrees * std::numbers::pi / 180.0);
}

// Where the pixel's ray meets the wall z = 0 (every pixel does: the wall fills the view).
DVec wallPoint(int x, int y) {
    const DVec d = pixelDirection(x, y);
    return kEye + d * (kEye.z / -d.z);
}

// ambient * albedo + I * strength * (albedo (n.l) + specular (n.h)^shininess), for a lit point of the wall.
double blinnPhong(double ambient, double albedo, double specular, double shininess, double intensity, double strength,
                  DVec p, DVec light) {
    const DVec l = unit(light - p), v = unit(kEye - p), h = unit(l + v);
    const double nl = dot(kWallNormal, l);
    if (nl <= 0) return ambient * albedo;
    return ambient * albedo +
           intensity * strength * (albedo * nl + specular * std::pow(std::max(0.0, dot(kWallNormal, h)), shininess));
}

Material wallMaterial(float ambient, float albedo, float specular, float shininess) {
    Material m;
    m.ambient = Rgb{ambient};
    m.diffuse = Rgb{albedo};
    m.specular = Rgb{specular};
    m.shininess = shininess;
    return m;
}

Light pointLightAt(DVec p, float intensity) {
    Light l;
    l.type = LightType::Point;
    l.position = Vec3{static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
    l.intensity = Rgb{intensity};
    return l;
}

}  // namespace

// A sharp highlight (shininess 200) from a point light: every pixel as the
// model says (no falloff: the light is as bright at 4 units as at 1), and the
// brightest pixel where the eye's mirror image, the wall and the light line up.
TEST(AnalyticLights, BlinnPhongHighlightOfAPointLight) {
    const DVec light{1, 1, 2};
    Scene scene;
    scene.camera = analyticCamera();
    scene.objects.push_back(wallAtZeroFacingCamera(wallMaterial(0.05f, 0.1f, 1.0f, 200.0f)));
    scene.lights.push_back(pointLightAt(light, 0.8f));
    scene.environment = Environment::constant(Rgb{0.0f});
    const Image image = renderAnalytic(scene);

    int peakX = 0, peakY = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const double want = blinnPhong(0.05, 0.1, 1.0, 200.0, 0.8, 1.0, wallPoint(x, y), light);
            const Rgb& got = image.at(x, y);
            EXPECT_NEAR(got.r, want, kTolerance) << x << "," << y;
            EXPECT_EQ(got.r, got.g) << x << "," << y;
            EXPECT_EQ(got.r, got.b) << x << "," << y;
            if (got.r > image.at(peakX, peakY).r) peakX = x, peakY = y;
        }
    // n.h = 1 where the line from the eye's mirror image (0,0,-5) to the light
    // crosses the wall: (0,0,-5) + s ((1,1,2) - (0,0,-5)) at z = 0, s = 5/7.
    int wantX = 0, wantY = 0;
    pixelOf({5.0 / 7.0, 5.0 / 7.0, 0.0}, wantX, wantY);
    EXPECT_NEAR(peakX, wantX, 1) << "highlight peak";
    EXPECT_NEAR(peakY, wantY, 1) << "highlight peak";
    EXPECT_GT(image.at(peakX, peakY).r, 0.7f) << "a peak of nearly the light's intensity";
}

// A spot light straight at the wall: full strength inside cone - falloff,
// smoothstep to zero at the cone, ambient only outside; the cone's edge
// (radius 3 tan 20 degrees = 1.09) lies inside the view (half-width 1.82).
TEST(AnalyticLights, SpotLightConeOnAWall) {
    const DVec position{0, 0, 3};
    Scene scene;
    scene.camera = analyticCamera();
    scene.objects.push_back(wallAtZeroFacingCamera(wallMaterial(0.1f, 0.6f, 0.0f, 1.0f)));
    Light spot = pointLightAt(position, 1.5f);
    spot.type = LightType::Spot;
    spot.direction = Vec3{0, 0, -1};
    spot.coneAngleDeg = 20.0f;
    spot.falloffAngleDeg = 8.0f;
    scene.lights.push_back(spot);
    const Image image = renderAnalytic(scene);

    int full = 0, fading = 0, dark = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const DVec p = wallPoint(x, y);
            const double cosOffAxis = dot(unit(p - position), {0, 0, -1});
            const double strength = smoothstepD(cosDeg(20.0), cosDeg(12.0), cosOffAxis);
            const double want = blinnPhong(0.1, 0.6, 0.0, 1.0, 1.5, strength, p, position);
            EXPECT_NEAR(image.at(x, y).r, want, kTolerance) << x << "," << y << " strength " << strength;
            full += strength == 1.0;
            fading += strength > 0.0 && strength < 1.0;
            dark += strength == 0.0;
        }
    // All three regimes are in the picture, so each was checked.
    EXPECT_GT(full, 200);
    EXPECT_GT(fading, 200);
    EXPECT_GT(dark, 200);
}

// A sphere between a point light and the wall: a wall point is dark (ambient
// only) exactly when the segment from it to the light crosses the sphere.
TEST(AnalyticLights, SphereShadowOnAWall) {
    const DVec light{1.2, 0.9, 4.0}, center{0, 0, 1};
    constexpr double kRadius = 0.5;
    Scene scene;
    scene.camera = analyticCamera();
    scene.objects.push_back(wallAtZeroFacingCamera(wallMaterial(0.1f, 0.7f, 0.0f, 1.0f)));
    scene.objects.push_back(SceneObject{"ball", Sphere{{0, 0, 1}, static_cast<float>(kRadius)}, Material{}, {0, 0, 1}});
    scene.lights.push_back(pointLightAt(light, 1.0f));
    const Image image = renderAnalytic(scene);

    int shadowed = 0, lit = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const DVec d = pixelDirection(x, y);
            const SphereHit seen = raySphere(kEye, d, center, kRadius);
            if (std::fabs(seen.disc) < 1e-3 || (seen.disc > 0 && seen.tNear > 0)) continue;  // the ball, or its rim
            const DVec p = wallPoint(x, y);
            const DVec toLight = light - p;
            const SphereHit blocker = raySphere(p, unit(toLight), center, kRadius);
            if (std::fabs(blocker.disc) < 1e-3) continue;  // the shadow's edge, within rounding
            const bool inShadow = blocker.disc > 0 && blocker.tNear > 0 && blocker.tNear < length(toLight);
            const double want = inShadow ? 0.1 * 0.7 : blinnPhong(0.1, 0.7, 0.0, 1.0, 1.0, 1.0, p, light);
            EXPECT_NEAR(image.at(x, y).r, want, kTolerance) << x << "," << y << (inShadow ? " (shadow)" : " (lit)");
            (inShadow ? shadowed : lit) += 1;
        }
    EXPECT_GT(shadowed, 100) << "the shadow is in view";
    EXPECT_GT(lit, 1000);
}
