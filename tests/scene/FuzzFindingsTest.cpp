// Every input the fuzzers found (tests/fuzz/findings/, docs/testing.md) goes
// through the loader its fuzzer fed (a glTF file through both, as a mesh and
// as a scene): it loads, or gives one InputError naming the file, never a
// crash, a hang or another exception. A new finding is
// tested by adding its file there; one of an unknown kind fails here until
// this test knows its loader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <set>
#include <string>

#include "core/Errors.h"
#include "scene/GltfScene.h"
#include "scene/ImageLoader.h"
#include "scene/MeshLoader.h"

namespace raycache {
namespace {

const std::filesystem::path findingsDir =
    std::filesystem::path(RAYCACHE_TEST_DATA_DIR).parent_path() / "fuzz" / "findings";

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// The loader each fuzzer feeds, by the extensions its first byte picks.
std::function<void(const std::filesystem::path&)> loaderFor(const std::filesystem::path& path) {
    static const std::set<std::string> images = {".png", ".jpg", ".bmp", ".tga", ".hdr", ".exr"};
    static const std::set<std::string> meshes = {".obj", ".gltf", ".glb", ".off", ".stl", ".dae", ".ply"};
    const std::string ext = lowerExtension(path);
    if (images.count(ext)) return [](const std::filesystem::path& p) { (void)loadImageFile(p); };
    // A glTF file is fed to both of its loaders (fuzz_mesh_loader, fuzz_gltf_scene).
    if (ext == ".gltf" || ext == ".glb")
        return [](const std::filesystem::path& p) {
            try {
                (void)loadMeshFile(p);
            } catch (const InputError& e) {
                EXPECT_EQ(e.where().file, p.string()) << e.what();
                EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
            }
            (void)loadGltfScene(p);
        };
    if (meshes.count(ext)) return [](const std::filesystem::path& p) { (void)loadMeshFile(p); };
    return nullptr;
}

TEST(FuzzFindings, EachLoadsOrIsOneErrorNamingTheFile) {
    int tested = 0;
    for (const auto& entry : std::filesystem::directory_iterator(findingsDir)) {
        const std::filesystem::path& path = entry.path();
        if (!entry.is_regular_file() || path.extension() == ".md") continue;
        SCOPED_TRACE(path.string());
        const auto load = loaderFor(path);
        ASSERT_TRUE(load) << "no loader known for this finding's extension";
        try {
            load(path);
        } catch (const InputError& e) {
            const std::string what = e.what();
            EXPECT_EQ(e.where().file, path.string()) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
        ++tested;
    }
    EXPECT_GE(tested, 6);
}

}  // namespace
}  // namespace raycache
