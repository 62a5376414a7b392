// The caching cubes' memory budget (cache/CubeBudget.h): the planned bytes
// against what RayCache really allocates, which cubes are lowered, the
// refusal of a scene that cannot fit, and 100 000 caching spheres rendered
// within 256 MiB.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cache/CubeBudget.h"
#include "cache/RayCache.h"
#include "core/Errors.h"
#include "core/Parallel.h"
#include "render/FrameRenderer.h"
#include "trace/TraceScene.h"

using namespace raycache;

namespace {

constexpr std::size_t kMiB = 1024 * 1024;

// `count` caching mirror spheres of radius `radius`, 400 to a row in the z = 0 plane.
Scene spheres(int count, float radius, int resolution, CacheTechnique technique = CacheTechnique::Cct) {
    Scene s;
    Material mirror;
    mirror.reflectivity = 0.6f;
    mirror.cache = {technique, resolution};
    for (int i = 0; i < count; ++i) {
        const Vec3 c{static_cast<float>(i % 400) * 3.0f * radius, static_cast<float>(i / 400) * 3.0f * radius, 0};
        s.objects.push_back(SceneObject{"s" + std::to_string(i), Sphere{c, radius}, mirror, c});
    }
    return s;
}

}  // namespace

TEST(CubeBudget, PlannedBytesCoverWhatTheCacheAllocates) {
    // RayCache::bytes() counts texel words (and levels, blocks), not validity
    // bits: the plan is that plus 1/32 of the colour words.
    for (const int levels : {1, 4}) {
        for (const CacheTechnique technique : {CacheTechnique::Cct, CacheTechnique::Cdct}) {
            RayCacheSettings settings;
            settings.cubeLevels = levels;
            const Scene scene = spheres(3, 1.0f, 128, technique);
            const RayCache cache(scene, settings);
            const std::size_t planned = 3 * cubeBytes(technique != CacheTechnique::Cct, 128, levels, false);
            EXPECT_GE(planned, cache.bytes());
            EXPECT_LE(planned, cache.bytes() + cache.bytes() / 20) << levels;
        }
    }
}

TEST(CubeBudget, NothingChangesWithinTheBudget) {
    const std::vector<CubeRequest> cubes{{"a", false, 512, 1.0f}, {"b", true, 256, 2.0f}};
    for (const std::optional<std::size_t> budget : {std::optional<std::size_t>{}, std::optional<std::size_t>{1ull << 40}}) {
        const CubeBudgetPlan plan = planCubeBudget(cubes, budget, 1, false, 4);
        EXPECT_EQ(plan.resolutions, (std::vector<int>{512, 256}));
        EXPECT_EQ(plan.lowered, 0);
        EXPECT_TRUE(plan.note.empty());
        EXPECT_EQ(plan.bytes, plan.askedBytes);
    }
}

TEST(CubeBudget, SmallObjectsLoseResolutionFirstUntilTheCubesFit) {
    // Two small objects and a large one, 512² each (6.2 MiB with their
    // validity bits): a 10 MiB budget lowers the small ones to 256² only.
    const std::vector<CubeRequest> cubes{{"small1", false, 512, 0.5f}, {"large", false, 512, 5.0f},
                                         {"small2", false, 512, 0.5f}};
    const CubeBudgetPlan plan = planCubeBudget(cubes, 10 * kMiB, 1, false, 4);
    EXPECT_LE(plan.bytes, 10 * kMiB);
    EXPECT_EQ(plan.resolutions[1], 512);
    EXPECT_EQ(plan.resolutions[0], 256);
    EXPECT_EQ(plan.resolutions[2], 256);
    EXPECT_EQ(plan.lowered, 2);
    EXPECT_NE(plan.note.find("lowered 2 of 3 cubes"), std::string::npos) << plan.note;
    // Tighter: the large one goes too, and the plan still fits.
    const CubeBudgetPlan tight = planCubeBudget(cubes, 2 * kMiB, 1, false, 4);
    EXPECT_LE(tight.bytes, 2 * kMiB);
    EXPECT_LT(tight.resolutions[1], 512);
}

TEST(CubeBudget, ASceneThatCannotFitIsRefusedBeforeAnythingIsAllocated) {
    RayCacheSettings settings;
    settings.memoryBudget = 64 * 1024;  // 64 KiB: 200 cubes need ~80 KiB even at 4²
    const Scene scene = spheres(200, 1.0f, 512);
    try {
        RayCache::validate(scene, settings);
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("200 objects"), std::string::npos) << what;
        EXPECT_NE(what.find("--cache-budget"), std::string::npos) << what;
    }
    EXPECT_THROW(RayCache(scene, settings), InputError);
}

TEST(CubeBudget, HundredThousandCachingSpheresRenderWithin256MiB) {
    RenderSettings settings;
    settings.width = settings.height = 48;
    settings.threads = 2;
    settings.cache.memoryBudget = 256 * kMiB;
    Scene scene = spheres(100000, 0.1f, 512);
    scene.lights.push_back(Light{});
    scene.camera.position = Vec3{60, 40, 80};
    scene.camera.lookAt = Vec3{60, 40, 0};
    RayCache cache(scene, settings.cache);
    EXPECT_LE(cache.bytes(), 256 * kMiB);
    EXPECT_NE(cache.budgetNote().find("lowered 100000 of 100000 cubes"), std::string::npos) << cache.budgetNote();
    const TraceScene tracer(scene);
    const Parallel parallel(2);
    const FrameRenderer renderer(scene, tracer, settings, parallel, &cache);
    Image film;
    for (int frame = 0; frame < 2; ++frame) {
        const FrameStats stats = renderer.render(scene.camera, film);
        ASSERT_TRUE(stats.cache.has_value());
        EXPECT_GT(stats.cache->lookups(), 0u);
        if (frame == 1) {
            EXPECT_GT(stats.cache->hits(), 0u);
        }
    }
}
