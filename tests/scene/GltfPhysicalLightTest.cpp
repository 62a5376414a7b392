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
// roughness^2, height-correlated Smith, Schlick's F from f0, 0.04 by
// default, to f90; KHR_materials_specular sets them for a dielectric).
double gltfBrdf(double baseColor, double roughness, double nl, double nv, double nh, double vh, double f0 = 0.04,
                double f90 = 1.0) {
    const double a2 = std::pow(roughness, 4.0);
    const double d = a2 / (std::numbers::pi * std::pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
    const double vis = 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
    const double f = f0 + (f90 - f0) * std::pow(1.0 - vh, 5.0);
    return baseColor / std::numbers::pi + d * vis * f;
}

// The pixel under the camera 3 above a 40 x 40 plane of `material`, lit by
// a point light of 683 * 10 cd at (1.5, 2, 0): d = 2.5, cos(theta) = 0.8.
// The geometry the expected values need is returned in `view`.
struct PlaneView {
    double irradiance, nl, nv, nh, vh;
};
Rgb planeUnderAPointLight(const nlohmann::json& material, PlaneView& view) {
    const TempDir dir;
    GltfTestFile file;
    const int index = file.addMaterial(material);
    if (material.contains("extensions"))
        for (const auto& [name, value] : material["extensions"].items()) file.useExtension(name);
    file.addNode({{"mesh", file.addMesh(makePlane(), index)}, {"scale", {40, 1, 40}}});
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

    const double d2 = lx * lx + ly * ly, d = std::sqrt(d2);
    const double hx = lx / d, hy = ly / d + 1.0, hLength = std::sqrt(hx * hx + hy * hy);
    view = {candela / 683.0 / d2 * (ly / d), ly / d, 1.0, hy / hLength, hy / hLength};
    return film.at(16, 16);
}

TEST(GltfPhysicalLight, LambertPlaneUnderAPointLight) {
    const double base[3] = {0.8, 0.5, 0.2};
    PlaneView v;
    const Rgb seen = planeUnderAPointLight(
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {base[0], base[1], base[2], 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}},
        v);
    const float channels[3] = {seen.r, seen.g, seen.b};
    for (int i = 0; i < 3; ++i) {
        const double expected = gltfBrdf(base[i], 1.0, v.nl, v.nv, v.nh, v.vh) * v.irradiance;
        EXPECT_NEAR(channels[i], expected, 2e-3 * expected) << "channel " << i;
        // The Lambert term alone is most of it (the lobe at roughness 1 is small).
        EXPECT_NEAR(channels[i], base[i] / std::numbers::pi * v.irradiance, 0.1 * expected) << "channel " << i;
    }
}

// KHR_materials_specular, as Blender writes a Principled BSDF's specular 0
// (specularColorFactor 0: F0 = 0, F90 = specularFactor = 1), and a half
// specularFactor with a coloured specularColorFactor (F0 = 0.04 * colour *
// 0.5, F90 = 0.5), on a smoother plane whose highlight the pixel sees.
TEST(GltfPhysicalLight, SpecularExtensionSetsTheLobesFresnel) {
    const double base = 0.5, roughness = 0.5;
    const nlohmann::json pbr = {
        {"baseColorFactor", {base, base, base, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", roughness}};
    PlaneView v;
    const Rgb plain = planeUnderAPointLight({{"pbrMetallicRoughness", pbr}}, v);
    const Rgb none = planeUnderAPointLight(
        {{"pbrMetallicRoughness", pbr},
         {"extensions", {{"KHR_materials_specular", {{"specularColorFactor", {0.0, 0.0, 0.0}}}}}}},
        v);
    const Rgb tinted = planeUnderAPointLight(
        {{"pbrMetallicRoughness", pbr},
         {"extensions",
          {{"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularColorFactor", {2.0, 1.0, 0.0}}}}}}},
        v);
    const auto expected = [&](double f0, double f90) {
        return gltfBrdf(base, roughness, v.nl, v.nv, v.nh, v.vh, f0, f90) * v.irradiance;
    };
    EXPECT_NEAR(plain.r, expected(0.04, 1.0), 2e-3 * expected(0.04, 1.0));
    EXPECT_NEAR(none.r, expected(0.0, 1.0), 2e-3 * expected(0.0, 1.0));
    EXPECT_NEAR(none.g, expected(0.0, 1.0), 2e-3 * expected(0.0, 1.0));
    EXPECT_NEAR(tinted.r, expected(0.04, 0.5), 2e-3 * expected(0.04, 0.5));
    EXPECT_NEAR(tinted.g, expected(0.02, 0.5), 2e-3 * expected(0.02, 0.5));
    EXPECT_NEAR(tinted.b, expected(0.0, 0.5), 2e-3 * expected(0.0, 0.5));
    // The lobe is a visible share here: without it the pixel is darker.
    EXPECT_LT(none.r, plain.r * 0.97f);
}

}  // namespace
}  // namespace raycache
