// The glTF models of Debian's assimp-testmodels as whole scenes: each loads
// or is one InputError (no other exception, no crash, no hang), and the
// Khronos samples among them load with the notes they call for.
//
// assimp-testmodels is installed by scripts/install-deps.sh; without it
// these tests are skipped, saying so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "TextPattern.h"
#include "core/Errors.h"
#include "scene/GltfScene.h"

namespace raycache {
namespace {

namespace fs = std::filesystem;

const fs::path kAssimpModels = "/usr/share/assimp/models";

// The files `dpkg -L assimp-testmodels | grep -i -E 'gltf2?/.*\.(gltf|glb)$'` lists.
std::vector<fs::path> gltfModels() {
    std::vector<fs::path> files;
    const test::TextPattern pattern("gltf2?/.*\\.(gltf|glb)$", true);
    for (const auto& entry : fs::recursive_directory_iterator(kAssimpModels))
        if (entry.is_regular_file() && pattern.occursIn(entry.path().string())) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::size_t notesWith(const Scene& scene, const std::string& words) {
    return static_cast<std::size_t>(std::count_if(scene.notes.begin(), scene.notes.end(), [&](const std::string& n) {
        return n.find(words) != std::string::npos;
    }));
}

#define SKIP_WITHOUT_ASSIMP_MODELS()                                            \
    if (!fs::is_directory(kAssimpModels))                                       \
    GTEST_SKIP() << kAssimpModels                                               \
                 << " is missing: Debian's assimp-testmodels is not installed " \
                    "(scripts/install-deps.sh installs it)"

TEST(GltfRealModels, EveryModelLoadsAsASceneOrIsOneError) {
    SKIP_WITHOUT_ASSIMP_MODELS();
    const std::vector<fs::path> files = gltfModels();
    ASSERT_GT(files.size(), 40u);
    std::size_t loaded = 0;
    for (const fs::path& file : files) {
        try {
            const Scene scene = loadGltfScene(file);
            EXPECT_FALSE(scene.objects.empty()) << file;
            EXPECT_FALSE(scene.lights.empty()) << file;
            for (const std::string& n : scene.notes) EXPECT_EQ(n.find('\n'), std::string::npos) << n;
            ++loaded;
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
            EXPECT_EQ(e.where().file, file.string()) << e.what();
        }
    }
    std::printf("%zu of %zu assimp-testmodels glTF files load as scenes\n", loaded, files.size());
}

TEST(GltfRealModels, KhronosSamplesLoadWithTheirNotes) {
    SKIP_WITHOUT_ASSIMP_MODELS();
    const Scene box = loadGltfScene(kAssimpModels / "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb");
    ASSERT_EQ(box.objects.size(), 1u);
    EXPECT_TRUE(box.objects[0].material.diffuseTexture.has_value());
    EXPECT_EQ(notesWith(box, "no camera in the file"), 1u);
    EXPECT_EQ(notesWith(box, "no lights in the file"), 1u);

    const Scene skin = loadGltfScene(kAssimpModels / "glTF2/simple_skin/simple_skin.gltf");
    EXPECT_EQ(notesWith(skin, "ignored the skins of 1 mesh"), 1u);
    EXPECT_EQ(notesWith(skin, "ignored 1 animation"), 1u);

    const Scene morph =
        loadGltfScene(kAssimpModels / "glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
    EXPECT_EQ(notesWith(morph, "ignored the morph targets of 1 mesh"), 1u);
    EXPECT_EQ(notesWith(morph, "ignored 1 animation"), 1u);

    // Its first camera is a perspective one at (0.5, 0.5, 3), the second orthographic.
    const Scene cameras = loadGltfScene(kAssimpModels / "glTF2/cameras/Cameras.gltf");
    EXPECT_EQ(cameras.camera.position, (Vec3{0.5f, 0.5f, 3.0f}));
    EXPECT_NEAR(cameras.camera.verticalFovDeg, 0.7 * 180.0 / 3.14159265358979, 1e-4);
    EXPECT_EQ(notesWith(cameras, "ignored 1 orthographic camera"), 1u);

    const Scene clearcoat = loadGltfScene(kAssimpModels / "glTF2/ClearCoat-glTF/ClearCoatTest.gltf");
    EXPECT_EQ(notesWith(clearcoat, "ignored extension KHR_materials_clearcoat"), 1u);
}

TEST(GltfRealModels, UnreadableModelsNameWhatTheyNeed) {
    SKIP_WITHOUT_ASSIMP_MODELS();
    const auto refusal = [](const fs::path& file) -> std::string {
        try {
            (void)loadGltfScene(kAssimpModels / file);
        } catch (const InputError& e) {
            return e.what();
        }
        return "loaded";
    };
    EXPECT_NE(refusal("glTF2/draco/2CylinderEngine.gltf").find("requires the extension KHR_draco_mesh_compression"),
              std::string::npos);
    EXPECT_NE(refusal("glTF/TwoBoxes/TwoBoxes.gltf").find("glTF 1.0"), std::string::npos);
    EXPECT_NE(refusal("glTF2/IndexOutOfRange/IndexOutOfRange.gltf").find("out-of-range indices"), std::string::npos);
}

}  // namespace
}  // namespace raycache
