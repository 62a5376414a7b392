// glTF 2.0 files as whole scenes (scene/GltfScene.h): small files written
// here load as the same scene written in our JSON renders (the mapping
// rules of docs/scene-format.md, "glTF 2.0 scenes", written out by hand in
// the JSON), and what raycache cannot show is one note, what it cannot read
// one error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "GltfTestFile.h"
#include "TempDir.h"
#include "core/Errors.h"
#include "metrics/ImageMetrics.h"
#include "render/ImageWriter.h"
#include "scene/GltfScene.h"
#include "scene/MeshGenerators.h"
#include "scene/PbrToBlinnPhong.h"
#include "scene/SceneFile.h"
#include "scene/SceneLoader.h"
#include "session/RenderSession.h"

namespace raycache {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string number(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.9g", v);
    return buffer;
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

// An 8x8 checkerboard of two colours, as an sRGB PNG.
fs::path writeCheckerPng(const fs::path& path) {
    Image image(8, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) image.at(x, y) = (x + y) % 2 ? Rgb(0.8f, 0.2f, 0.1f) : Rgb(0.1f, 0.5f, 0.9f);
    writeImage(image, path);
    return path;
}

Image render(const Scene& scene, CacheTechnique technique) {
    RenderSettings settings;
    settings.width = settings.height = 64;
    settings.threads = 2;
    settings.cache.techniqueOverride = technique;
    settings.cache.resolutionOverride = 64;
    RenderSession session(scene, settings);
    Image film;
    session.render(scene.camera, film);
    return film;
}

// The two scenes render alike: identical, or at least 50 dB apart (the glTF
// node matrices and our transforms round differently in the last bits).
void expectSameRenders(const Scene& gltf, const Scene& ours) {
    for (CacheTechnique technique : {CacheTechnique::None, CacheTechnique::Cct}) {
        const Image a = render(gltf, technique), b = render(ours, technique);
        EXPECT_EQ(countNonFinitePixels(a), 0);
        EXPECT_GE(psnr(a, b), 50.0) << "technique " << cacheTechniqueName(technique);
    }
}

bool hasNoteWith(const Scene& scene, const std::string& words) {
    for (const std::string& n : scene.notes)
        if (n.find(words) != std::string::npos) return true;
    return false;
}

std::string allNotes(const Scene& scene) {
    std::string s;
    for (const std::string& n : scene.notes) s += n + "\n";
    return s;
}

class GltfSceneTest : public ::testing::Test {
protected:
    fs::path path(const std::string& name) const { return dir_.path() / name; }

    // A file of one mesh at the origin: what a JSON mesh object reads.
    fs::path meshFile(const std::string& name, const TriangleMesh& mesh) const {
        GltfTestFile file;
        file.addNode({{"mesh", file.addMesh(mesh)}});
        file.write(path(name));
        return path(name);
    }

    // Loads and expects one InputError whose one line holds `words`.
    void expectRefused(const fs::path& file, const std::string& words) const {
        try {
            (void)loadGltfScene(file);
            ADD_FAILURE() << file << " loaded";
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_EQ(e.where().file, file.string());
            EXPECT_NE(what.find(words), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }

    TempDir dir_;
};

// A textured floor, a mirror ball, a glass box, a point, a spot and a
// directional light and a camera, against the same scene in our JSON.
TEST_F(GltfSceneTest, LoadsAsTheSameSceneWrittenInOurJson) {
    const fs::path png = writeCheckerPng(path("checker.png"));
    TriangleMesh plane = makePlane();
    const TriangleMesh sphere = uvSphere(1.0f), box = makeBox();

    GltfTestFile file;
    const int checker = file.addTexture(fileBytes(png));
    const int floorMaterial = file.addMaterial(
        {{"name", "floor"},
         {"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", checker}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}}});
    const int chrome = file.addMaterial(
        {{"name", "chrome"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.9, 0.9, 0.9, 1.0}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.05}}}});
    file.useExtension("KHR_materials_transmission");
    file.useExtension("KHR_materials_ior");
    const int glass = file.addMaterial(
        {{"name", "glass"},
         {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.0}}},
         {"extensions",
          {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}, {"KHR_materials_ior", {{"ior", 1.45}}}}}});
    file.addNode({{"name", "floor"}, {"mesh", file.addMesh(plane, floorMaterial)}, {"scale", {8, 1, 8}}});
    file.addNode({{"name", "mirror"}, {"mesh", file.addMesh(sphere, chrome)}, {"translation", {-1.2, 1, 0}}});
    file.addNode({{"name", "glass"},
                  {"mesh", file.addMesh(box, glass)},
                  {"translation", {1.3, 0.6, 0.5}},
                  {"rotation", quaternion(0, 1, 0, 30)},
                  {"scale", {1.2, 1.2, 1.2}}});
    // Camera 3 up and 9 back, turned 15 degrees down about x.
    file.addNode({{"name", "eye"},
                  {"camera", file.addCamera({{"type", "perspective"},
                                             {"perspective", {{"yfov", 0.7}, {"aspectRatio", 1.0}, {"znear", 0.1}}}})},
                  {"translation", {0, 3, 9}},
                  {"rotation", quaternion(1, 0, 0, -15)}});
    file.addNode({{"name", "bulb"},
                  {"translation", {3, 6, 4}},
                  {"extensions",
                   {{"KHR_lights_punctual",
                     {{"light", file.addLight({{"type", "point"}, {"color", {1, 0.9, 0.8}}, {"intensity", 40}})}}}}}});
    // Straight down: the node turns its -z to -y.
    file.addNode({{"name", "spot"},
                  {"translation", {-3, 5, 2}},
                  {"rotation", quaternion(1, 0, 0, -90)},
                  {"extensions",
                   {{"KHR_lights_punctual",
                     {{"light", file.addLight({{"type", "spot"},
                                               {"intensity", 30},
                                               {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}})}}}}}});
    file.addNode(
        {{"name", "sun"},
         {"rotation", quaternion(1, 0, 0, -60)},
         {"extensions",
          {{"KHR_lights_punctual", {{"light", file.addLight({{"type", "directional"}, {"intensity", 0.3}})}}}}}});
    file.write(path("scene.gltf"));

    meshFile("plane.gltf", plane);
    meshFile("sphere.gltf", sphere);
    meshFile("box.gltf", box);
    // glTF's lights are physical (inverse-square falloff, glTF's spot cone),
    // their candela and lux made W/sr and W/m^2 by 683 lm/W.
    const double lumensPerWatt = 683.0;
    const double pointScale = 40.0 / lumensPerWatt;
    const double spotIntensity = 30.0 / lumensPerWatt;
    const double degrees = 180.0 / std::numbers::pi;
    const double down15 = 15.0 / degrees, down60 = 60.0 / degrees;
    // Glass: F0 = ((ior - 1) / (ior + 1))^2 reflected, the rest transmitted.
    const double f0 = std::pow(0.45 / 2.45, 2.0);
    const std::string ours =
        R"({
      "camera": {"position": [0, 3, 9], "lookAt": [0, )" +
        number(3 - std::sin(down15)) + ", " + number(9 - std::cos(down15)) + R"(],
                 "up": [0, )" +
        number(std::cos(down15)) + ", " + number(-std::sin(down15)) + R"(], "fov": )" + number(0.7 * degrees) + R"(},
      "environment": {"type": "color", "color": [0, 0, 0]},
      "lights": [
        {"type": "point", "position": [3, 6, 4], "intensity": [)" +
        number(pointScale) + ", " + number(0.9 * pointScale) + ", " + number(0.8 * pointScale) + R"(], "physical": true},
        {"type": "spot", "position": [-3, 5, 2], "direction": [0, -1, 0], "intensity": )" +
        number(spotIntensity) + R"(, "cone": )" + number(0.5 * degrees) + R"(, "falloff": )" + number(0.3 * degrees) +
        R"(, "physical": true},
        {"type": "directional", "direction": [0, )" +
        number(-std::sin(down60)) + ", " + number(-std::cos(down60)) +
        R"(], "intensity": )" + number(0.3 / lumensPerWatt) + R"(, "physical": true}
      ],
      "objects": [
        {"name": "floor", "shape": "mesh", "file": "plane.gltf", "transform": {"scale": [8, 1, 8]},
         "material": {"texture": {"type": "image", "file": "checker.png"},
                      "specular": 0.095, "shininess": 30}},
        {"name": "mirror", "shape": "mesh", "file": "sphere.gltf", "transform": {"translate": [-1.2, 1, 0]},
         "material": {"diffuse": )" +
        number(0.9 * 0.1) + R"(, "specular": 1, "shininess": 4096, "kr": 0.9,
                      "cache": {"technique": "cct"}}},
        {"name": "glass", "shape": "mesh", "file": "box.gltf",
         "transform": {"translate": [1.3, 0.6, 0.5], "rotate": {"axis": [0, 1, 0], "degrees": 30}, "scale": 1.2},
         "material": {"diffuse": 0, "specular": 1, "shininess": 4096, "kr": )" +
        number(f0) + R"(, "kt": )" + number(1.0 - f0) + R"(, "ior": 1.45, "cache": {"technique": "cct"}}}
      ]
    })";
    writeText(path("ours.json"), ours);

    // The Blinn-Phong mapping, which the JSON above writes out by hand.
    const Scene gltf = loadGltfScene(path("scene.gltf"), GltfSceneOverrides{.blinnPhongMaterials = true});
    const Scene ourJson = loadSceneFile(path("ours.json"));
    EXPECT_TRUE(gltf.notes.empty()) << allNotes(gltf);
    ASSERT_EQ(gltf.objects.size(), 3u);
    EXPECT_EQ(gltf.objects[0].name, "floor");
    EXPECT_EQ(gltf.objects[1].name, "mirror");
    EXPECT_EQ(gltf.objects[2].name, "glass");
    const Material& mirror = gltf.objects[1].material;
    EXPECT_FLOAT_EQ(mirror.reflectivity, 0.9f);
    EXPECT_EQ(mirror.cache.technique, CacheTechnique::Cct);
    const Material& glassMaterial = gltf.objects[2].material;
    EXPECT_NEAR(glassMaterial.transmissivity, 1.0 - f0, 1e-6);
    EXPECT_FLOAT_EQ(glassMaterial.ior, 1.45f);
    EXPECT_EQ(glassMaterial.cache.technique, CacheTechnique::Cct);
    ASSERT_EQ(gltf.lights.size(), 3u);
    EXPECT_EQ(gltf.lights[1].type, LightType::Spot);
    EXPECT_NEAR(gltf.lights[1].coneAngleDeg, 0.5 * degrees, 1e-4);
    EXPECT_NEAR(gltf.lights[1].falloffAngleDeg, 0.3 * degrees, 1e-4);
    EXPECT_NEAR(gltf.camera.verticalFovDeg, 0.7 * degrees, 1e-4);
    expectSameRenders(gltf, ourJson);
}

// The camera and lights a file without them gets, each with its note.
TEST_F(GltfSceneTest, WithoutCameraAndLightsFramesTheSceneAndLightsItOverTheShoulder) {
    GltfTestFile file;
    file.addNode({{"mesh", file.addMesh(makeBox())}, {"translation", {10, 0, 0}}});
    file.write(path("bare.gltf"));
    const Scene scene = loadGltfScene(path("bare.gltf"));
    ASSERT_EQ(scene.notes.size(), 2u) << allNotes(scene);
    EXPECT_TRUE(hasNoteWith(scene, "no camera in the file: a camera framed on the scene's bounds is used"));
    EXPECT_TRUE(hasNoteWith(scene, "no lights in the file"));
    EXPECT_EQ(scene.camera.lookAt, (Vec3{10, 0, 0}));
    EXPECT_EQ(scene.camera.verticalFovDeg, 45.0f);
    // The unit box's bounding sphere (radius sqrt(3) / 2) fills the view's height with a tenth to spare.
    const float distance = length(scene.camera.position - scene.camera.lookAt);
    EXPECT_NEAR(distance, 1.1 * std::sqrt(3.0) / 2.0 / std::sin(22.5 * std::numbers::pi / 180.0), 1e-4);
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].type, LightType::Directional);
    // From behind, above and the left: along the view, downwards, to the right.
    const Vec3 forward = normalize(scene.camera.lookAt - scene.camera.position);
    EXPECT_GT(dot(scene.lights[0].direction, forward), 0.5f);
    EXPECT_LT(scene.lights[0].direction.y, 0.0f);
    // Physical, pi W/m^2: a white Lambert surface facing it shows 1.
    EXPECT_TRUE(scene.lights[0].physical);
    EXPECT_FLOAT_EQ(scene.lights[0].intensity.r, std::numbers::pi_v<float>);
    // A glTF file has no environment: black, as Blender renders it.
    EXPECT_EQ(scene.environment.lookup({0, 1, 0}), (Rgb{0.0f, 0.0f, 0.0f}));
}

// The base colour factor multiplies the texture: baked into the texture's pixels.
TEST_F(GltfSceneTest, BaseColourFactorMultipliesTheTexture) {
    const fs::path png = writeCheckerPng(path("checker.png"));
    GltfTestFile file;
    const int texture = file.addTexture(fileBytes(png));
    const int material = file.addMaterial({{"pbrMetallicRoughness",
                                            {{"baseColorTexture", {{"index", texture}}},
                                             {"baseColorFactor", {0.5, 1, 0.25, 1}},
                                             {"metallicFactor", 0.0}}}});
    file.addNode({{"mesh", file.addMesh(makePlane(), material)}});
    file.write(path("tinted.gltf"));
    const Scene scene = loadGltfScene(path("tinted.gltf"));
    const Material& m = scene.objects.at(0).material;
    ASSERT_TRUE(m.diffuseTexture.has_value());
    ASSERT_TRUE(m.diffuseTexture->pixels());
    const Image& baked = *m.diffuseTexture->pixels();
    const Image original = [&] {
        // The same PNG, as a JSON scene reads it.
        writeText(
            path("plain.json"),
            R"({"objects": [{"shape": "plane", "material": {"texture": {"type": "image", "file": "checker.png"}}}]})");
        return *loadSceneFile(path("plain.json")).objects[0].material.diffuseTexture->pixels();
    }();
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const Rgb o = original.at(x, y), b = baked.at(x, y);
            EXPECT_FLOAT_EQ(b.r, o.r * 0.5f);
            EXPECT_FLOAT_EQ(b.g, o.g);
            EXPECT_FLOAT_EQ(b.b, o.b * 0.25f);
        }
}

// Under glTF's BRDF a gold mirror reflects gold and glass transmits tinted by
// its base colour factor (the rays' weights, tests/render/SecondaryRayWeights.h):
// no note says otherwise, but one says a glass texture does not tint; under
// the Blinn-Phong mapping both are untinted, and notes say so.
TEST_F(GltfSceneTest, ColouredMirrorsAndGlassAreTintedUnderTheBrdf) {
    const fs::path png = writeCheckerPng(path("checker.png"));
    GltfTestFile file;
    const int texture = file.addTexture(fileBytes(png));
    const int gold = file.addMaterial({{"name", "gold"},
                                       {"pbrMetallicRoughness",
                                        {{"baseColorFactor", {1.0, 0.77, 0.34, 1}}, {"roughnessFactor", 0.0}}}});
    const int glass = file.addMaterial(
        {{"name", "green glass"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.2, 0.9, 0.3, 1}},
           {"baseColorTexture", {{"index", texture}}},
           {"metallicFactor", 0.0},
           {"roughnessFactor", 0.0}}},
         {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 0.8}}}}}});
    file.useExtension("KHR_materials_transmission");
    file.addNode({{"mesh", file.addMesh(makeBox(), gold)}});
    file.addNode({{"mesh", file.addMesh(makePlane(), glass)}});
    file.write(path("tinted.gltf"));

    const Scene brdf = loadGltfScene(path("tinted.gltf"));
    ASSERT_EQ(brdf.objects.size(), 2u);
    const Material& mirror = brdf.objects[0].material;
    EXPECT_EQ(mirror.model, ShadingModel::MetallicRoughness);
    EXPECT_TRUE(mirror.reflects());
    EXPECT_FALSE(mirror.refracts());
    EXPECT_EQ(mirror.diffuse, (Rgb{1.0f, 0.77f, 0.34f}));  // the base colour F0 is taken from
    const Material& pane = brdf.objects[1].material;
    EXPECT_TRUE(pane.reflects());
    EXPECT_FLOAT_EQ(pane.transmissivity, 0.8f);
    EXPECT_EQ(pane.transmissionTint, (Rgb{0.2f, 0.9f, 0.3f}));
    EXPECT_FALSE(hasNoteWith(brdf, "untinted")) << allNotes(brdf);
    EXPECT_TRUE(hasNoteWith(brdf, "1 glass material's transmission is tinted by the base colour factor only"))
        << allNotes(brdf);

    const Scene mapped = loadGltfScene(path("tinted.gltf"), GltfSceneOverrides{.blinnPhongMaterials = true});
    EXPECT_TRUE(hasNoteWith(mapped, "1 mirror material reflects untinted")) << allNotes(mapped);
    EXPECT_TRUE(hasNoteWith(mapped, "1 glass material transmits untinted")) << allNotes(mapped);
    EXPECT_FALSE(hasNoteWith(mapped, "tinted by the base colour factor only")) << allNotes(mapped);
}

// KHR_texture_transform gives what the transformed texture coordinates give.
TEST_F(GltfSceneTest, TextureTransformIsBakedIntoTheTextureCoordinates) {
    const fs::path png = writeCheckerPng(path("checker.png"));
    const double offsetU = 0.3, offsetV = -0.2, rotation = 0.6, scaleU = 2.0, scaleV = 0.5;
    const auto writeScene = [&](const fs::path& out, bool withExtension) {
        TriangleMesh plane = makePlane();
        if (!withExtension) {
            // The extension's uv' = T R S uv, in glTF's texture space (v down).
            for (auto& uv : plane.uvs) {
                const double u = uv[0], v = 1.0 - uv[1];
                const double su = scaleU * u, sv = scaleV * v;
                const double tu = std::cos(rotation) * su + std::sin(rotation) * sv + offsetU;
                const double tv = -std::sin(rotation) * su + std::cos(rotation) * sv + offsetV;
                uv = {static_cast<float>(tu), static_cast<float>(1.0 - tv)};
            }
        }
        GltfTestFile file;
        json info = {{"index", file.addTexture(fileBytes(png))}};
        if (withExtension) {
            file.useExtension("KHR_texture_transform");
            info["extensions"]["KHR_texture_transform"] = {
                {"offset", {offsetU, offsetV}}, {"rotation", rotation}, {"scale", {scaleU, scaleV}}};
        }
        const int material =
            file.addMaterial({{"pbrMetallicRoughness", {{"baseColorTexture", info}, {"metallicFactor", 0.0}}}});
        file.addNode({{"mesh", file.addMesh(plane, material)}, {"scale", {4, 1, 4}}});
        file.addNode(
            {{"camera", file.addCamera({{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}})},
             {"translation", {0, 5, 0}},
             {"rotation", quaternion(1, 0, 0, -90)}});
        file.write(out);
    };
    writeScene(path("transformed.gltf"), true);
    writeScene(path("baked.gltf"), false);
    const Scene transformed = loadGltfScene(path("transformed.gltf"));
    const Scene baked = loadGltfScene(path("baked.gltf"));
    const auto& a = std::get<MeshShape>(transformed.objects.at(0).shape).mesh->uvs;
    const auto& b = std::get<MeshShape>(baked.objects.at(0).shape).mesh->uvs;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(a[i][0], b[i][0], 1e-5) << i;
        EXPECT_NEAR(a[i][1], b[i][1], 1e-5) << i;
    }
    const Image ia = render(transformed, CacheTechnique::None), ib = render(baked, CacheTechnique::None);
    EXPECT_GE(psnr(ia, ib), 50.0);
}

// Skins, morph targets and animations: each one note. (The skin: Debian's
// assimp-testmodels, tests/scene/GltfRealModelsTest.cpp.)
TEST_F(GltfSceneTest, MorphTargetsAndAnimationsAreOneNoteEach) {
    GltfTestFile file;
    const TriangleMesh box = makeBox();
    const int mesh = file.addMesh(box);
    // A morph target moving every vertex up: the accessor of the first mesh's positions will do.
    file.document()["meshes"][mesh]["primitives"][0]["targets"] = {{{"POSITION", 0}}};
    file.document()["meshes"][mesh]["weights"] = {0.0};
    const int node = file.addNode({{"name", "box"}, {"mesh", mesh}});
    // A translation animation of the box's node: key times and values in a second buffer view.
    const float times[] = {0.0f, 1.0f};
    const float values[] = {0, 0, 0, 0, 1, 0};
    std::vector<unsigned char> bytes(sizeof times + sizeof values);
    std::memcpy(bytes.data(), times, sizeof times);
    std::memcpy(bytes.data() + sizeof times, values, sizeof values);
    json& d = file.document();
    const std::size_t views = d["bufferViews"].size(), accessors = d["accessors"].size();
    d["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", 0}, {"byteLength", sizeof times}});
    d["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", sizeof times}, {"byteLength", sizeof values}});
    d["accessors"].push_back({{"bufferView", views},
                              {"componentType", 5126},
                              {"count", 2},
                              {"type", "SCALAR"},
                              {"min", {0.0}},
                              {"max", {1.0}}});
    d["accessors"].push_back({{"bufferView", views + 1}, {"componentType", 5126}, {"count", 2}, {"type", "VEC3"}});
    d["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}}}},
                        {"samplers", {{{"input", accessors}, {"output", accessors + 1}}}}}};
    file.write(path("moving.gltf"));
    // write() sets the one buffer; add the animation's as the second.
    json written = json::parse(std::ifstream(path("moving.gltf")));
    written["buffers"].push_back(
        {{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}});
    writeText(path("moving.gltf"), written.dump());

    const Scene scene = loadGltfScene(path("moving.gltf"));
    int morphs = 0, animations = 0;
    for (const std::string& n : scene.notes) {
        morphs += n.find("morph targets") != std::string::npos;
        animations += n.find("animation") != std::string::npos;
    }
    EXPECT_EQ(morphs, 1) << allNotes(scene);
    EXPECT_EQ(animations, 1) << allNotes(scene);
    EXPECT_TRUE(hasNoteWith(scene, "ignored 1 animation: the scene is drawn still")) << allNotes(scene);
}

// What raycache cannot read is one error naming the file and what is wrong.
TEST_F(GltfSceneTest, WhatCannotBeReadIsOneErrorNamingIt) {
    {
        GltfTestFile file;
        file.addNode({{"mesh", file.addMesh(makeBox())}});
        file.document()["extensionsRequired"] = {"EXT_meshopt_compression"};
        file.document()["extensionsUsed"] = {"EXT_meshopt_compression"};
        file.write(path("meshopt.gltf"));
        expectRefused(path("meshopt.gltf"),
                      "requires the extension EXT_meshopt_compression, which raycache cannot read");
    }
    {
        GltfTestFile file;
        file.addNode({{"mesh", file.addMesh(makeBox())}});
        file.document()["asset"]["version"] = "1.0";
        file.write(path("old.gltf"));
        expectRefused(path("old.gltf"), "glTF 1.0: raycache reads glTF 2.0 scenes");
    }
    writeText(path("broken.gltf"), "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [,]\n}\n");
    expectRefused(path("broken.gltf"), "not valid glTF JSON");
    try {
        (void)loadGltfScene(path("broken.gltf"));
    } catch (const InputError& e) {
        EXPECT_EQ(e.where().line, 3);
    }
    {
        GltfTestFile file;
        const int material = file.addMaterial({{"name", "shiny"}, {"pbrMetallicRoughness", {{"metallicFactor", 2.0}}}});
        file.addNode({{"mesh", file.addMesh(makeBox(), material)}});
        file.write(path("metal.gltf"));
        expectRefused(path("metal.gltf"), "material 'shiny': metallicFactor 2 is outside [0, 1]");
    }
    {
        GltfTestFile file;
        const int image = static_cast<int>(file.document()["images"].size());
        file.document()["images"].push_back({{"uri", "missing%20image.png"}});
        file.document()["textures"].push_back({{"source", image}});
        const int material =
            file.addMaterial({{"name", "paper"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
        file.addNode({{"mesh", file.addMesh(makePlane(), material)}});
        file.write(path("untextured.gltf"));
        expectRefused(path("untextured.gltf"),
                      "material 'paper': base colour texture file not found: \"missing%20image.png\"");
    }
    {
        GltfTestFile file;
        file.addNode({{"mesh", file.addMesh(makeBox())}});
        file.addNode(
            {{"name", "eye"},
             {"camera", file.addCamera({{"type", "perspective"}, {"perspective", {{"yfov", 0.0}, {"znear", 0.1}}}})}});
        file.write(path("blind.gltf"));
        expectRefused(path("blind.gltf"), "camera 'eye': vertical field of view 0 degrees, must be between 0 and 180");
    }
    {
        GltfTestFile file;
        file.addNode({{"mesh", file.addMesh(makeBox())}});
        const int light = file.addLight({{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}});
        file.addNode({{"name", "lamp"}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
        file.write(path("wide.gltf"));
        expectRefused(path("wide.gltf"), "light 'lamp': outerConeAngle 2 must lie in (0, pi/2]");
    }
    {
        GltfTestFile file;
        file.addNode({{"name", "nothing"}});
        file.write(path("empty.gltf"));
        expectRefused(path("empty.gltf"), "holds no meshes");
    }
    expectRefused(path("absent.glb"), "scene file not found");
}

// `--scene` takes a glTF file by its extension, in any case: not as our JSON
// (which answered `unknown key "asset"`).
TEST_F(GltfSceneTest, SceneLoaderTakesGltfFilesByTheirExtension) {
    GltfTestFile file;
    file.addNode({{"mesh", file.addMesh(makeBox())}});
    file.write(path("Box.GLTF"));
    const Scene scene = loadScene(path("Box.GLTF").string());
    EXPECT_EQ(scene.name, "Box");
    EXPECT_EQ(scene.objects.size(), 1u);
    EXPECT_TRUE(isGltfPath("a/b.glb"));
    EXPECT_TRUE(isGltfPath("a/b.Gltf"));
    EXPECT_FALSE(isGltfPath("a/b.json"));
}

// "include": a glTF scene inside our JSON, our keys changing it: the camera's
// given keys, the lights replaced, the environment, an included object's
// material, objects added after the file's.
TEST_F(GltfSceneTest, IncludedInAJsonSceneOurKeysOverrideIt) {
    GltfTestFile file;
    const int red = file.addMaterial({{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}}});
    file.addNode({{"name", "floor"}, {"mesh", file.addMesh(makePlane(), red)}, {"scale", {8, 1, 8}}});
    file.addNode({{"name", "ball"}, {"mesh", file.addMesh(uvSphere(1.0f), red)}, {"translation", {0, 1, 0}}});
    file.addNode({{"name", "bulb"},
                  {"translation", {0, 5, 0}},
                  {"extensions",
                   {{"KHR_lights_punctual", {{"light", file.addLight({{"type", "point"}, {"intensity", 10}})}}}}}});
    file.write(path("model.glb.gltf"));
    const Scene alone = loadGltfScene(path("model.glb.gltf"));

    writeText(path("with.json"), R"({
      "include": {"file": "model.glb.gltf", "materials": {"ball": "chrome"}},
      "camera": {"fov": 30},
      "environment": {"type": "color", "color": 0.2},
      "lights": [{"type": "directional", "direction": [0, -1, 0], "intensity": 0.5}],
      "materials": {"chrome": {"diffuse": 0.05, "kr": 0.9, "cache": {"technique": "cdct"}}},
      "objects": [{"name": "extra", "shape": "sphere", "center": [3, 1, 0]}]
    })");
    const Scene scene = loadSceneFile(path("with.json"));
    EXPECT_EQ(scene.name, "with");
    ASSERT_EQ(scene.objects.size(), 3u);
    EXPECT_EQ(scene.objects[0].name, "floor");
    EXPECT_EQ(scene.objects[1].name, "ball");
    EXPECT_EQ(scene.objects[2].name, "extra");
    EXPECT_EQ(scene.objects[0].material.diffuse, alone.objects[0].material.diffuse);
    EXPECT_EQ(scene.objects[1].material.reflectivity, 0.9f);
    EXPECT_EQ(scene.objects[1].material.cache.technique, CacheTechnique::Cdct);
    // The framed camera, with our field of view; no note about the camera, since ours is given.
    EXPECT_EQ(scene.camera.position, alone.camera.position);
    EXPECT_EQ(scene.camera.verticalFovDeg, 30.0f);
    ASSERT_EQ(scene.lights.size(), 1u);
    EXPECT_EQ(scene.lights[0].type, LightType::Directional);
    EXPECT_EQ(scene.environment.lookup({0, 1, 0}), Rgb(0.2f));
    EXPECT_TRUE(scene.notes.empty()) << allNotes(scene);
    EXPECT_EQ(alone.notes.size(), 1u) << allNotes(alone);  // the file alone has no camera

    // The same file without our keys is the file's scene.
    writeText(path("bare.json"), R"({"include": "model.glb.gltf"})");
    const Scene bare = loadSceneFile(path("bare.json"));
    EXPECT_EQ(bare.objects.size(), 2u);
    EXPECT_EQ(bare.lights.size(), 1u);
    EXPECT_EQ(bare.notes, alone.notes);

    const auto refusal = [&](const std::string& text) -> std::string {
        writeText(path("bad.json"), text);
        try {
            (void)loadSceneFile(path("bad.json"));
        } catch (const InputError& e) {
            return e.what();
        }
        return "loaded";
    };
    EXPECT_NE(refusal(R"({"include": "model.glb.gltf", "objects": [{"name": "ball", "shape": "box"}]})")
                  .find("duplicate object name \"ball\" (also used by /include, an object of the included file)"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"include": {"file": "model.glb.gltf", "materials": {"bal": {"kr": 1}}}})")
                  .find("/include/materials/bal: the included file has no object \"bal\" (did you mean \"ball\"?)"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"include": "with.json"})").find("the included file must be a glTF 2.0 scene"),
              std::string::npos);
    EXPECT_NE(refusal(R"({"include": "nothere.glb"})").find("included scene file not found"), std::string::npos);
    writeText(path("broken.gltf"), "{]");
    EXPECT_NE(refusal(R"({"include": "broken.gltf"})").find("/include: cannot load included scene \"broken.gltf\": "),
              std::string::npos);
}

// The material rule's numbers (docs/scene-format.md, "Materials").
TEST(PbrToBlinnPhong, FollowsTheDocumentedRule) {
    EXPECT_EQ(blinnPhongShininess(0.5f), 30.0f);   // alpha 0.25: 2 / 0.0625 - 2
    EXPECT_EQ(blinnPhongShininess(0.3f), 245.0f);  // alpha 0.09: 2 / 0.0081 - 2 = 244.9
    EXPECT_EQ(blinnPhongShininess(1.0f), 0.0f);
    EXPECT_EQ(blinnPhongShininess(0.0f), 4096.0f);

    PbrMaterial rough;  // glTF's default material: a rough white metal
    Material m = blinnPhongFromPbr(rough);
    EXPECT_EQ(pbrMaterialKind(rough), PbrMaterialKind::Diffuse);
    EXPECT_EQ(m.diffuse, Rgb(1.0f));
    EXPECT_TRUE(m.specular.isBlack());
    EXPECT_EQ(m.cache.technique, CacheTechnique::None);

    PbrMaterial plastic;
    plastic.baseColor = {0.8f, 0.1f, 0.1f};
    plastic.metallic = 0.0f;
    plastic.roughness = 0.5f;
    m = blinnPhongFromPbr(plastic);
    EXPECT_EQ(m.diffuse, plastic.baseColor);
    EXPECT_NEAR(m.specular.r, 0.04 * 0.5 * 38.0 / 8.0, 1e-6);
    EXPECT_EQ(m.shininess, 30.0f);

    PbrMaterial gold;
    gold.baseColor = {1.0f, 0.8f, 0.3f};
    gold.metallic = 1.0f;
    gold.roughness = 0.0f;
    m = blinnPhongFromPbr(gold);
    EXPECT_EQ(pbrMaterialKind(gold), PbrMaterialKind::Mirror);
    EXPECT_FLOAT_EQ(m.reflectivity, 0.2126f + 0.7152f * 0.8f + 0.0722f * 0.3f);
    EXPECT_FLOAT_EQ(m.diffuse.g, 0.8f * (1.0f - m.reflectivity));
    EXPECT_EQ(m.cache.technique, CacheTechnique::Cct);

    PbrMaterial frosted;  // rough glass is still glass; half transmissive
    frosted.metallic = 0.0f;
    frosted.roughness = 0.6f;
    frosted.transmission = 0.5f;
    m = blinnPhongFromPbr(frosted);
    EXPECT_EQ(pbrMaterialKind(frosted), PbrMaterialKind::Glass);
    EXPECT_NEAR(m.reflectivity, 0.04, 1e-6);
    EXPECT_NEAR(m.transmissivity, 0.5 * 0.96, 1e-6);
    EXPECT_EQ(m.diffuse, Rgb(0.5f));
}

}  // namespace
}  // namespace raycache
