// A glTF scene's light in physical units, rendered: a diffuse plane under a
// point light of I candela at distance d shows, at the pixel that sees the
// point below the camera, baseColor / pi * (I / 683) / d^2 * cos(theta),
// plus the GGX lobe of a roughness-1 dielectric, both written out here from
// the glTF specification (Appendix B) and KHR_lights_punctual.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "GltfTestFile.h"
#include "TempDir.h"
#include "scene/GltfScene.h"
#include "scene/MeshGenerators.h"
#include "session/RenderSession.h"

namespace raycache {
namespace {

// glTF 2.0's BRDF for one light, in double: Lambert plus GGX (alpha =
// roughness^2, height-correlated Smith, Schlick's F with F0 = 0.04).
double gltfBrdf(double baseColor, double roughness, double nl, double nv, double nh, double vh) {
    const double a2 = std::pow(roughness, 4.0);
    const double d = a2 / (std::numbers::pi * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
    const double vis = 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
    const double f = 0.04 + 0.96 * std::pow(1.0 - vh, 5.0);
    return baseColor / std::numbers::pi + d * vis * f;
}

TEST(GltfPhysicalLight, LambertPlaneUnderAPointLight) {
    const TempDir dir;
    GltfTestFile file;
    const double base[3] = {0.8, 0.5, 0.2};
    const int material = file.addMaterial(
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {base[0], base[1], base[2], 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}});
    file.addNode({{"mesh", file.addMesh(makePlane(), material)}, {"scale", {40, 1, 40}}});
    // The camera 3 above the origin, looking straight down (-z turned to -y).
    const double s = std::sin(-std::numbers::pi / 4.0), c = std::cos(-std::numbers::pi / 4.0);
    file.addNode({{"camera", file.addCamera({{"type", "perspective"},
                                             {"perspective", {{"yfov", 0.5}, {"aspectRatio", 1.0}, {"znear", 0.1}}}})},
                  {"translation", {0, 3, 0}},
                  {"rotation", {s, 0, 0, c}}});
    const double candela = 683.0 * 10.0;  // 10 W/sr
    const double lx = 1.5, ly = 2.0;      // d = 2.5, cos(theta) = 0.8
    file.addNode({{"translation", {lx, ly, 0}},
                  {"extensions",
                   {{"KHR_lights_punctual", {{"light", file.addLight({{"type", "point"}, {"intensity", candela}})}}}}}});
    const std::filesystem::path path = dir.path() / "plane.gltf";
    file.write(path);
    const Scene scene = loadGltfScene(path);

    RenderSettings settings;
    settings.width = settings.height = 33;  // odd: the centre pixel's ray is the camera's axis
    settings.threads = 1;
    RenderSession session(scene, settings);
    Image film;
    session.render(scene.camera, film);
    const Rgb seen = film.at(16, 16);

    const double d2 = lx * lx + ly * ly, d = std::sqrt(d2);
    const double nl = ly / d, nv = 1.0;
    const double hx = lx / d, hy = ly / d + 1.0, hLength = std::sqrt(hx * hx + hy * hy);
    const double nh = hy / hLength, vh = hy / hLength;
    const double irradiance = candela / 683.0 / d2 * nl;
    const float channels[3] = {seen.r, seen.g, seen.b};
    for (int i = 0; i < 3; ++i) {
        const double expected = gltfBrdf(base[i], 1.0, nl, nv, nh, vh) * irradiance;
        EXPECT_NEAR(channels[i], expected, 2e-3 * expected) << "channel " << i;
        // The Lambert term alone is most of it (the lobe at roughness 1 is small).
        EXPECT_NEAR(channels[i], base[i] / std::numbers::pi * irradiance, 0.1 * expected) << "channel " << i;
    }
}

}  // namespace
}  // namespace raycache
