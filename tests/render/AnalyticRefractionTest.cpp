// A glass ball (kt = 0.5, ior 1.5, nothing else: no reflection, no surface
// colour) in front of an environment cube whose six faces have six colours.
// Each pixel must show kt^2 times the face that the ray reaches after
// bending into the ball and out again by Snell's law, n1 sin(t1) = n2 sin(t2),
// computed here in double precision from the angles; a wrong index, a missing
// bend or a wrong side shows as a wrong face.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "AnalyticScene.h"

using namespace raycache;
using namespace raycache::analytic;

namespace {

constexpr double kIor = 1.5;

// Snell's law on a surface with unit normal n facing the incoming unit ray d,
// from index n1 into n2: the tangential part scales by n1/n2, the normal part
// is what keeps the result unit length. Nothing when sin(t2) > 1.
std::optional<DVec> snell(DVec d, DVec n, double n1, double n2) {
    const double cosI = -dot(d, n);
    const DVec tangential = (d + n * cosI) * (n1 / n2);
    const double sin2T = dot(tangential, tangential);
    if (sin2T > 1.0) return std::nullopt;
    return tangential - n * std::sqrt(1.0 - sin2T);
}

// GL cube-face order +x, -x, +y, -y, +z, -z; nothing within 1e-3 of an edge.
std::optional<std::size_t> cubeFace(DVec r) {
    const double ax = std::fabs(r.x), ay = std::fabs(r.y), az = std::fabs(r.z);
    const double major = std::max({ax, ay, az});
    const double second = ax + ay + az - major - std::min({ax, ay, az});
    if (major - second < 1e-3 * major) return std::nullopt;
    const int axis = major == ax ? 0 : (major == ay ? 1 : 2);
    const double component = axis == 0 ? r.x : (axis == 1 ? r.y : r.z);
    return static_cast<std::size_t>(2 * axis + (component < 0 ? 1 : 0));
}

}  // namespace

TEST(AnalyticRefraction, GlassBallBendsTheEnvironmentBySnellsLaw) {
    Material glass;
    glass.ambient = Rgb{0.0f};
    glass.diffuse = Rgb{0.0f};
    glass.transmissivity = 0.5f;
    glass.ior = static_cast<float>(kIor);
    Scene scene;
    scene.camera = analyticCamera();
    scene.objects.push_back(SceneObject{"glass", Sphere{{0, 0, 0}, 1.0f}, glass, {0, 0, 0}});
    const std::array<Rgb, 6> faceColors{Rgb{1, 0, 0}, Rgb{0, 1, 0}, Rgb{0, 0, 1},
                                        Rgb{1, 1, 0}, Rgb{0, 1, 1}, Rgb{1, 0, 1}};
    std::array<std::shared_ptr<const Image>, 6> faces;
    for (std::size_t f = 0; f < 6; ++f) {
        auto img = std::make_shared<Image>(1, 1);
        img->at(0, 0) = faceColors[f];
        faces[f] = img;
    }
    scene.environment = Environment::cubeFaces(faces);
    const Image image = renderAnalytic(scene);

    int checked = 0, bentToAnotherFace = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const DVec d = pixelDirection(x, y);
            const SphereHit in = raySphere(kEye, d, {0, 0, 0}, 1.0);
            if (std::fabs(in.disc) < 1e-2) continue;  // grazing: float and double may disagree
            if (in.disc < 0) {
                const auto face = cubeFace(d);
                if (face) {
                    EXPECT_EQ(image.at(x, y), faceColors[*face]) << x << "," << y << " (background)";
                }
                continue;
            }
            const DVec entry = kEye + d * in.tNear;  // unit sphere: the point is the outward normal
            const auto inside = snell(d, entry, 1.0, kIor);
            ASSERT_TRUE(inside.has_value());  // air into glass always refracts
            const SphereHit through = raySphere(entry, *inside, {0, 0, 0}, 1.0);
            const DVec exit = entry + *inside * through.tFar;
            // Inside a sphere the exit angle equals the entry's refracted angle: never total reflection.
            const auto out = snell(*inside, exit * -1.0, kIor, 1.0);
            ASSERT_TRUE(out.has_value()) << x << "," << y;
            const auto face = cubeFace(*out);
            if (!face) continue;
            EXPECT_EQ(image.at(x, y), faceColors[*face] * 0.25f) << x << "," << y << ": expected face " << *face;
            ++checked;
            // A ball that did not bend light would show the face straight behind it.
            if (cubeFace(d) != face) ++bentToAnotherFace;
        }
    EXPECT_GT(checked, 400);
    EXPECT_GT(bentToAnotherFace, 100) << "too few pixels where refraction changes the face: the test would not see it";
}
