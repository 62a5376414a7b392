// A glTF material's emission, rendered: emissiveFactor times
// KHR_materials_emissive_strength's emissiveStrength is the radiance a
// black, unlit surface shows (the extension's definition), and a strength
// that is not a finite number >= 0 refuses the file naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "GltfTestFile.h"
#include "TempDir.h"
#include "core/Errors.h"
#include "scene/GltfScene.h"
#include "scene/MeshGenerators.h"
#include "session/RenderSession.h"

namespace raycache {
namespace {

// Two black planes side by side seen from above, unlit: the left one's
// material glows emissiveFactor alone, the right one's emissiveFactor
// times `strength` (a JSON value, so that tests can also write a wrong one).
GltfTestFile twoGlowingPlanes(const nlohmann::json& strength) {
    GltfTestFile file;
    const nlohmann::json black = {{"baseColorFactor", {0.0, 0.0, 0.0, 1.0}}, {"metallicFactor", 0.0}};
    const int plain = file.addMaterial({{"pbrMetallicRoughness", black}, {"emissiveFactor", {0.5, 0.25, 0.125}}});
    const int strong =
        file.addMaterial({{"pbrMetallicRoughness", black},
                          {"emissiveFactor", {0.5, 0.25, 0.125}},
                          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}}}});
    file.useExtension("KHR_materials_emissive_strength");
    file.addNode({{"mesh", file.addMesh(makePlane(), plain)}, {"translation", {-1.0, 0, 0}}});
    file.addNode({{"mesh", file.addMesh(makePlane(), strong)}, {"translation", {1.0, 0, 0}}});
    // A sun shining straight up (its -z turned to +y), from below the planes
    // the camera sees from above: they are unlit, and no default light is added.
    file.addNode(
        {{"rotation", quaternion(1, 0, 0, 90.0)},
         {"extensions",
          {{"KHR_lights_punctual", {{"light", file.addLight({{"type", "directional"}, {"intensity", 1000.0}})}}}}}});
    const double s = std::sin(-std::numbers::pi / 4.0), c = std::cos(-std::numbers::pi / 4.0);
    file.addNode({{"camera", file.addCamera({{"type", "perspective"},
                                             {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}}}})},
                  {"translation", {0, 4, 0}},
                  {"rotation", {s, 0, 0, c}}});
    return file;
}

TEST(GltfEmission, StrengthMultipliesTheEmissiveFactor) {
    const TempDir dir;
    const std::filesystem::path path = dir.path() / "glow.gltf";
    twoGlowingPlanes(4.0).write(path);
    const Scene scene = loadGltfScene(path);
    for (const std::string& note : scene.notes)
        EXPECT_EQ(note.find("KHR_materials_emissive_strength"), std::string::npos) << note;

    RenderSettings settings;
    settings.width = 64;
    settings.height = 32;
    settings.threads = 1;
    RenderSession session(scene, settings);
    Image film;
    session.render(scene.camera, film);
    // A quarter of the way in from each side: inside the left and the right plane.
    const Rgb left = film.at(16, 16), right = film.at(48, 16);
    EXPECT_EQ(left.r, 0.5f);
    EXPECT_EQ(left.g, 0.25f);
    EXPECT_EQ(left.b, 0.125f);
    EXPECT_EQ(right.r, 2.0f);
    EXPECT_EQ(right.g, 1.0f);
    EXPECT_EQ(right.b, 0.5f);
}

TEST(GltfEmission, AStrengthThatIsNotAFiniteNumberAtLeastZeroIsOneErrorNamingTheField) {
    const TempDir dir;
    for (const nlohmann::json& wrong : {nlohmann::json(-1.0), nlohmann::json("bright"), nlohmann::json(1e300)}) {
        const std::filesystem::path path = dir.path() / "wrong.gltf";
        twoGlowingPlanes(wrong).write(path);
        try {
            (void)loadGltfScene(path);
            ADD_FAILURE() << "emissiveStrength " << wrong.dump() << " loaded";
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_EQ(e.where().file, path.string());
            EXPECT_NE(what.find("materials[1].extensions.KHR_materials_emissive_strength.emissiveStrength"),
                      std::string::npos)
                << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

}  // namespace
}  // namespace raycache
