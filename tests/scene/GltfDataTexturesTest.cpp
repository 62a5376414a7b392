// glTF's data textures, rendered: a normal texture turns the shading normal
// in the frame of the texture coordinates (a constant texel under a sun
// gives the cosine of the tilted normal, analytically), and a
// metallic-roughness texture gives each hit the metallic (blue) and
// roughness (green) that an untextured material with those factors has.
// Both are read as data (byte / 255), not as sRGB colours.
#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "GltfTestFile.h"
#include "TempDir.h"
#include "core/Errors.h"
#include "scene/GltfScene.h"
#include "scene/MeshGenerators.h"
#include "session/RenderSession.h"

namespace raycache {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using Texel = std::array<unsigned char, 3>;

// A PNG of `width` x `height` bytes, `texelAt(x, y)` each.
template <typename TexelAt>
std::vector<unsigned char> pngOf(int width, int height, TexelAt texelAt, const fs::path& scratch) {
    std::vector<unsigned char> bytes;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Texel t = texelAt(x, y);
            bytes.insert(bytes.end(), t.begin(), t.end());
        }
    EXPECT_NE(stbi_write_png(scratch.c_str(), width, height, 3, bytes.data(), width * 3), 0);
    return fileBytes(scratch);
}

float byteValue(unsigned char b) { return static_cast<float>(b) / 255.0f; }

// A 4 x 4 plane at y = 0 (texture u along +x, v along +z) seen from 4 above,
// under a sun shining toward -toLight; `material` is its glTF material.
GltfTestFile planeUnderSun(GltfTestFile file, const json& material, const Vec3& toLight) {
    const int m = file.addMaterial(material);
    file.addNode({{"mesh", file.addMesh(makePlane(), m)}, {"scale", {4, 1, 4}}});
    // The light shines along its node's -z: turn -z onto -toLight, about the
    // axis cross(-z, -toLight).
    const Vec3 from{0, 0, -1}, to = -normalize(toLight);
    const Vec3 axis = normalize(cross(from, to));
    const double degrees = std::acos(static_cast<double>(dot(from, to))) * 180.0 / 3.14159265358979323846;
    file.addNode(
        {{"rotation", quaternion(axis.x, axis.y, axis.z, degrees)},
         {"extensions",
          {{"KHR_lights_punctual", {{"light", file.addLight({{"type", "directional"}, {"intensity", 683.0}})}}}}}});
    file.addNode({{"camera", file.addCamera({{"type", "perspective"},
                                             {"perspective", {{"yfov", 0.5}, {"aspectRatio", 1.0}, {"znear", 0.1}}}})},
                  {"translation", {0, 4, 0}},
                  {"rotation", quaternion(1, 0, 0, -90.0)}});
    return file;
}

Image renderFrame(const Scene& scene) {
    RenderSettings settings;
    settings.width = settings.height = 32;
    settings.threads = 2;
    RenderSession session(scene, settings);
    Image film;
    session.render(scene.camera, film);
    return film;
}

// A material that shows only Lambert's diffuse (KHR_materials_specular's
// factor 0 takes the specular lobe away), with `normalTexture` if not null.
json diffuseMaterial(const json& normalTexture) {
    json m = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"metallicFactor", 0.0}}},
              {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}};
    if (!normalTexture.is_null()) m["normalTexture"] = normalTexture;
    return m;
}

class GltfDataTexturesTest : public ::testing::Test {
protected:
    fs::path path(const std::string& name) const { return dir_.path() / name; }

    Scene load(GltfTestFile file, const std::string& name, GltfSceneOverrides overrides = {}) const {
        file.useExtension("KHR_materials_specular");
        file.write(path(name));
        return loadGltfScene(path(name), overrides);
    }

    TempDir dir_;
};

TEST_F(GltfDataTexturesTest, AConstantNormalTextureTiltsLambertsCosine) {
    const Texel texel{200, 100, 230};
    const Vec3 toLight = normalize(Vec3{0.6f, 1.0f, -0.2f});
    const std::vector<unsigned char> png = pngOf(4, 4, [&](int, int) { return texel; }, path("normal.png"));
    for (const float scale : {1.0f, 0.5f}) {
        GltfTestFile textured;
        const int texture = textured.addTexture(png);
        json normalTexture = {{"index", texture}};
        if (scale != 1.0f) normalTexture["scale"] = scale;
        const Scene bumped = load(planeUnderSun(textured, diffuseMaterial(normalTexture), toLight), "bumped.gltf");
        const Scene flat = load(planeUnderSun(GltfTestFile{}, diffuseMaterial(nullptr), toLight), "flat.gltf");
        for (const std::string& note : bumped.notes) EXPECT_EQ(note.find("normal texture"), std::string::npos) << note;

        // Tangent space: x along the texture's u (world +x), y along its v
        // (world +z), z the plane's normal (world +y).
        const float x = (2.0f * byteValue(texel[0]) - 1.0f) * scale;
        const float y = (2.0f * byteValue(texel[1]) - 1.0f) * scale;
        const float z = 2.0f * byteValue(texel[2]) - 1.0f;
        const Vec3 tilted = normalize(Vec3{x, z, y});
        const double expected = dot(tilted, toLight) / toLight.y;

        const Image a = renderFrame(bumped), b = renderFrame(flat);
        for (const auto& [px, py] : std::array<std::array<int, 2>, 3>{{{16, 16}, {5, 9}, {27, 22}}}) {
            ASSERT_GT(b.at(px, py).g, 0.0f);
            EXPECT_NEAR(a.at(px, py).g / b.at(px, py).g, expected, 2e-5) << "scale " << scale << " pixel " << px;
        }
        // The mirrored frame (bitangent along -v) gives a clearly other answer:
        // the comparison can tell which way the texture's y turns the normal.
        EXPECT_GT(std::abs(dot(normalize(Vec3{x, z, -y}), toLight) / toLight.y - expected), 0.01);
    }
}

TEST_F(GltfDataTexturesTest, AMetallicRoughnessTextureShadesAsTheFactorsItHolds) {
    // Left half: metallic 1, roughness 128/255; right half: metallic 0, roughness 1.
    const Texel left{0, 128, 255}, right{0, 255, 0};
    const std::vector<unsigned char> png =
        pngOf(8, 8, [&](int x, int) { return x < 4 ? left : right; }, path("mr.png"));
    const Vec3 toLight = normalize(Vec3{0.5f, 1.0f, 0.3f});
    const json base = {{"baseColorFactor", {0.6, 0.5, 0.4, 1}}};

    GltfTestFile file;
    json textured = base;
    textured["metallicRoughnessTexture"] = {{"index", file.addTexture(png)}};
    const Scene scene = load(planeUnderSun(file, {{"pbrMetallicRoughness", textured}}, toLight), "mr.gltf");
    const Material& material = scene.objects.at(0).material;
    ASSERT_TRUE(material.metallicRoughnessTexture.has_value());
    for (const std::string& note : scene.notes) EXPECT_EQ(note.find("metallic-roughness"), std::string::npos) << note;
    // Read as data: the bytes / 255, no sRGB curve.
    const Rgb texel = material.metallicRoughnessTexture->pixels()->at(1, 1);
    EXPECT_EQ(texel.g, byteValue(128));
    EXPECT_EQ(texel.b, 1.0f);

    const auto untextured = [&](float metallic, float roughness, const std::string& name) {
        json factors = base;
        factors["metallicFactor"] = metallic;
        factors["roughnessFactor"] = roughness;
        return renderFrame(load(planeUnderSun(GltfTestFile{}, {{"pbrMetallicRoughness", factors}}, toLight), name));
    };
    const Image image = renderFrame(scene);
    const Image metal = untextured(1.0f, byteValue(128), "metal.gltf");
    const Image dielectric = untextured(0.0f, 1.0f, "dielectric.gltf");
    // The camera sees u in about [0.25, 0.75]: image x 8 lies on the left
    // half, 24 on the right, away from the texels the filter blends.
    for (int y : {8, 16, 24}) {
        const Rgb l = image.at(8, y), m = metal.at(8, y);
        const Rgb r = image.at(24, y), d = dielectric.at(24, y);
        EXPECT_NEAR(l.r, m.r, 1e-5f * m.r) << y;
        EXPECT_NEAR(l.b, m.b, 1e-5f * m.b) << y;
        EXPECT_NEAR(r.r, d.r, 1e-5f * d.r) << y;
        EXPECT_NEAR(r.b, d.b, 1e-5f * d.b) << y;
        EXPECT_GT(std::abs(m.r - d.r), 0.05f * d.r) << "the two halves must differ for the test to mean anything";
    }
}

TEST_F(GltfDataTexturesTest, ASmoothPlaceOnTheTextureMakesTheMaterialAMirror) {
    const Vec3 toLight{0, 1, 0};
    for (const int smallestByte : {0, 20, 30}) {
        const auto smallest = static_cast<unsigned char>(smallestByte);
        GltfTestFile file;
        const std::vector<unsigned char> png = pngOf(
            4, 4, [&](int x, int) { return Texel{0, static_cast<unsigned char>(x == 0 ? smallest : 200), 255}; },
            path("mr.png"));
        const json pbr = {{"metallicRoughnessTexture", {{"index", file.addTexture(png)}}}};
        const Scene scene = load(planeUnderSun(file, {{"pbrMetallicRoughness", pbr}}, toLight), "smooth.gltf");
        // Roughness factor 1 times the smallest green: below 0.1 somewhere.
        EXPECT_EQ(scene.objects.at(0).material.reflects(), byteValue(smallest) < kSmoothRoughness)
            << int{smallest};
    }
}

TEST_F(GltfDataTexturesTest, TheBlinnPhongMappingNotesTheTexturesItIgnores) {
    GltfTestFile file;
    const std::vector<unsigned char> png = pngOf(2, 2, [](int, int) { return Texel{128, 128, 255}; }, path("n.png"));
    const int texture = file.addTexture(png);
    const json material = {{"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", texture}}}}},
                           {"normalTexture", {{"index", texture}}}};
    const Scene mapped = load(planeUnderSun(file, material, {0, 1, 0}), "mapped.gltf",
                              GltfSceneOverrides{.blinnPhongMaterials = true});
    std::string notes;
    for (const std::string& note : mapped.notes) notes += note + "\n";
    EXPECT_NE(notes.find("ignored the normal textures of 1 material"), std::string::npos) << notes;
    EXPECT_NE(notes.find("ignored the metallic-roughness textures of 1 material"), std::string::npos) << notes;
    EXPECT_FALSE(mapped.objects.at(0).material.normalTexture.has_value());
}

TEST_F(GltfDataTexturesTest, ATextureOnOtherCoordinatesIsLeftOutWithANote) {
    GltfTestFile file;
    const std::vector<unsigned char> png = pngOf(2, 2, [](int, int) { return Texel{128, 128, 255}; }, path("n.png"));
    const int texture = file.addTexture(png);
    const json material = {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}},
                           {"normalTexture", {{"index", texture}, {"texCoord", 1}}}};
    const Scene scene = load(planeUnderSun(file, material, {0, 1, 0}), "two-sets.gltf");
    EXPECT_FALSE(scene.objects.at(0).material.normalTexture.has_value());
    std::string notes;
    for (const std::string& note : scene.notes) notes += note + "\n";
    EXPECT_NE(notes.find("ignored 1 texture whose texture coordinates"), std::string::npos) << notes;
}

TEST_F(GltfDataTexturesTest, AMissingNormalTextureIsOneErrorNamingIt) {
    GltfTestFile file;
    file.document()["images"] = json::array({{{"uri", "bumps.png"}}});
    file.document()["textures"] = json::array({{{"source", 0}}});
    const json material = {{"name", "bumpy"}, {"normalTexture", {{"index", 0}}}};
    try {
        (void)load(planeUnderSun(file, material, {0, 1, 0}), "missing.gltf");
        ADD_FAILURE() << "loaded";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(e.where().file, path("missing.gltf").string());
        EXPECT_NE(what.find("material 'bumpy': normal texture file not found: \"bumps.png\""), std::string::npos)
            << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

}  // namespace
}  // namespace raycache
