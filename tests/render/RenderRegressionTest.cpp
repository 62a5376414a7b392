// Small renders of built-in scenes against committed reference images, and
// bit-exact determinism across thread counts.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>

#include "core/Parallel.h"
#include "metrics/ImageMetrics.h"
#include "render/FrameRenderer.h"
#include "scene/BuiltinScenes.h"
#include "scene/ImageLoader.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

constexpr int kReferenceSide = 128;
// References were rendered by this renderer; the margin only absorbs
// floating-point differences between compilers and optimization levels.
constexpr double kMinPsnrAgainstReference = 45.0;

Image renderFrame(const Scene& scene, int threads, int size = kReferenceSide) {
    RenderSettings settings;
    settings.width = size;
    settings.height = size;
    settings.threads = threads;
    settings.cache.techniqueOverride = CacheTechnique::None;  // the uncached ground truth
    const TraceScene tracer(scene);
    const Parallel parallel(threads);
    const FrameRenderer renderer(scene, tracer, settings, parallel);
    Image film;
    renderer.render(scene.camera, film);
    return film;
}

class RenderRegression : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(RenderRegression, MatchesReferenceWithoutNaN) {
    const auto scene = makeBuiltinScene(GetParam());
    ASSERT_TRUE(scene.has_value());
    const Image image = renderFrame(*scene, 0);
    EXPECT_EQ(countNonFinitePixels(image), 0);
    const std::filesystem::path reference =
        std::filesystem::path(RAYCACHE_TEST_DATA_DIR) / "references" / (GetParam() + ".exr");
    const Image expected = loadImageFile(reference);
    const double db = psnr(image, expected);
    EXPECT_GE(db, kMinPsnrAgainstReference) << GetParam() << " differs from " << reference;
    RecordProperty("psnr_db", std::to_string(db));
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, RenderRegression,
                         ::testing::Values("behind-8", "grid-16", "diffuse-32", "room", "parallax", "glass",
                                           "shapes"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                             std::string name = param.param;
                             for (char& c : name)
                                 if (c == '-') c = '_';
                             return name;
                         });

TEST(RenderDeterminism, BitIdenticalAcrossThreadCounts) {
    for (const char* name : {"room", "glass"}) {
        const auto scene = makeBuiltinScene(name);
        ASSERT_TRUE(scene.has_value());
        const Image one = renderFrame(*scene, 1, 96);
        for (int threads : {2, 3, 8}) {
            const Image many = renderFrame(*scene, threads, 96);
            ASSERT_EQ(one.pixels().size(), many.pixels().size());
            EXPECT_EQ(std::memcmp(one.pixels().data(), many.pixels().data(), one.pixels().size() * sizeof(Rgb)), 0)
                << name << " with " << threads << " threads differs from 1 thread";
        }
        // And across runs with the same thread count.
        const Image again = renderFrame(*scene, 1, 96);
        EXPECT_EQ(std::memcmp(one.pixels().data(), again.pixels().data(), one.pixels().size() * sizeof(Rgb)), 0);
    }
}

TEST(RenderBasics, EveryBuiltinSceneRendersFiniteNonBlackImages) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const auto scene = makeBuiltinScene(info.name);
        ASSERT_TRUE(scene.has_value()) << info.name;
        const Image image = renderFrame(*scene, 0, 32);
        EXPECT_EQ(countNonFinitePixels(image), 0) << info.name;
        double sum = 0;
        for (const Rgb& p : image.pixels()) sum += p.r + p.g + p.b;
        EXPECT_GT(sum, 0.0) << info.name;
    }
}
