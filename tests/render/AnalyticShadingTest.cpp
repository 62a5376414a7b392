// Renders checked pixel by pixel against closed-form answers computed here in
// double precision, independently of the renderer's code paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "AnalyticScene.h"

using namespace raycache;
using namespace raycache::analytic;

namespace {

// Nearest positive hit of a ray from `o` on the unit sphere at the origin.
bool hitUnitSphere(DVec o, DVec d, double& t) {
    const double b = dot(o, d), c = dot(o, o) - 1.0, disc = b * b - c;
    if (disc < 0) return false;
    t = -b - std::sqrt(disc);
    return t > 0;
}

Scene unitSphereScene(const Material& material) {
    Scene s;
    s.objects.push_back(SceneObject{"ball", Sphere{{0, 0, 0}, 1.0f}, material, {0, 0, 0}});
    s.camera = analyticCamera();
    return s;
}

// Pixels whose ray passes within this distance of the silhouette are skipped:
// float and double may disagree there about hit or miss.
bool nearSilhouette(DVec o, DVec d) {
    const double b = dot(o, d), disc = b * b - (dot(o, o) - 1.0);
    return std::fabs(disc) < 1e-3;
}

}  // namespace

TEST(AnalyticShading, LambertSphereUnderDirectionalLight) {
    Material m;
    m.ambient = Rgb{0.1f};
    m.diffuse = Rgb{0.8f, 0.5f, 0.2f};
    Scene scene = unitSphereScene(m);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = normalize(Vec3{-1, -1, -1});
    sun.intensity = Rgb{1.0f};
    scene.lights.push_back(sun);
    scene.environment = Environment::constant(Rgb{0.25f, 0.5f, 0.75f});
    const Image image = renderAnalytic(scene);

    const DVec toLight = unit({1, 1, 1}), eye{0, 0, 5};
    int checked = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const DVec d = pixelDirection(x, y);
            if (nearSilhouette(eye, d)) continue;
            double t;
            const Rgb& got = image.at(x, y);
            if (!hitUnitSphere(eye, d, t)) {
                EXPECT_EQ(got, (Rgb{0.25f, 0.5f, 0.75f})) << x << "," << y;
                continue;
            }
            const DVec n = eye + d * t;  // unit sphere: the point is the normal
            // A convex sphere cannot shadow itself where n.l > 0.
            const double lambert = std::max(0.0, dot(n, toLight));
            EXPECT_NEAR(got.r, 0.1 * 0.8 + 0.8 * lambert, 2e-4) << x << "," << y;
            EXPECT_NEAR(got.g, 0.1 * 0.5 + 0.5 * lambert, 2e-4) << x << "," << y;
            EXPECT_NEAR(got.b, 0.1 * 0.2 + 0.2 * lambert, 2e-4) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 300);
}

TEST(AnalyticShading, MirrorSphereReflectsTheEnvironmentCube) {
    // A black mirror (no ambient, diffuse or highlight) shows kr times the
    // environment seen along the reflected direction; each cube face has its
    // own color, so a wrong reflection direction shows as a wrong color.
    Material m;
    m.ambient = Rgb{0.0f};
    m.diffuse = Rgb{0.0f};
    m.reflectivity = 0.5f;
    Scene scene = unitSphereScene(m);
    const std::array<Rgb, 6> faceColors{Rgb{1, 0, 0}, Rgb{0, 1, 0}, Rgb{0, 0, 1},
                                        Rgb{1, 1, 0}, Rgb{0, 1, 1}, Rgb{1, 0, 1}};
    std::array<std::shared_ptr<const Image>, 6> faces;
    for (int f = 0; f < 6; ++f) {
        auto img = std::make_shared<Image>(1, 1);
        img->at(0, 0) = faceColors[static_cast<std::size_t>(f)];
        faces[static_cast<std::size_t>(f)] = img;
    }
    scene.environment = Environment::cubeFaces(faces);
    const Image image = renderAnalytic(scene);

    const DVec eye{0, 0, 5};
    int checked = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const DVec d = pixelDirection(x, y);
            double t;
            if (nearSilhouette(eye, d) || !hitUnitSphere(eye, d, t)) continue;
            const DVec n = eye + d * t;
            const DVec r = d - n * (2.0 * dot(d, n));
            // Skip directions close to a cube edge, where float rounding may pick the neighbour face.
            const double ax = std::fabs(r.x), ay = std::fabs(r.y), az = std::fabs(r.z);
            const double major = std::max({ax, ay, az});
            const double second = ax + ay + az - major - std::min({ax, ay, az});
            if (major - second < 1e-3) continue;
            // GL face order: +x, -x, +y, -y, +z, -z.
            const int axis = major == ax ? 0 : (major == ay ? 1 : 2);
            const double component = axis == 0 ? r.x : (axis == 1 ? r.y : r.z);
            const auto face = static_cast<std::size_t>(2 * axis + (component < 0 ? 1 : 0));
            const Rgb expected = faceColors[face] * 0.5f;
            EXPECT_EQ(image.at(x, y), expected) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 300);
}
