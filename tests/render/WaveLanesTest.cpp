// The tile kernel's waves in lanes (RenderSettings::waveLanes,
// render/WaveLanes.cpp) against its general path, one record per hit: every
// lane does the general path's arithmetic, so images, ray counts and caches
// must be the same bit for bit, in the ray and the hybrid pipelines. Scenes
// cover spheres and meshes in one packet, textured spheres and meshes,
// point, spot and directional lights, glass, concave mirrors, animation,
// and tiles cut by the image's edge (83x61: neither side a multiple of 16).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "ImageCompare.h"
#include "CiRequirement.h"
#include "render/FrameRenderer.h"
#include "scene/BuiltinScenes.h"
#include "scene/MeshSearchPath.h"
#include "scene/RealMeshScenes.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

constexpr int kWidth = 83, kHeight = 61;

struct Frames {
    std::vector<Image> images;
    std::vector<FrameStats> stats;
};

Frames renderFrames(const Scene& scene, bool lanes, CacheTechnique technique, int frames,
                    PipelineKind pipeline = PipelineKind::Ray, bool idealCache = false) {
    RenderSettings settings;
    settings.pipeline = pipeline;
    settings.gbuffer = GBufferSource::Packets;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.threads = 2;
    settings.waveLanes = lanes;
    settings.cache.techniqueOverride = technique;
    settings.cache.resolutionOverride = 64;
    settings.cache.ideal = idealCache;
    RenderSession session(scene, settings);
    Frames out;
    for (int f = 0; f < frames; ++f) {
        if (!scene.animation.empty()) session.setTime(static_cast<float>(f) / scene.fps);
        Image image;
        out.stats.push_back(session.render(scene.cameraPath.cameraAt(scene.camera, f), image));
        out.images.push_back(std::move(image));
    }
    return out;
}

void expectLanesEqualGeneralPath(const Scene& scene, const std::string& name, CacheTechnique technique, int frames,
                                 PipelineKind pipeline = PipelineKind::Ray, bool idealCache = false) {
    const Frames lanes = renderFrames(scene, true, technique, frames, pipeline, idealCache);
    const Frames general = renderFrames(scene, false, technique, frames, pipeline, idealCache);
    for (int f = 0; f < frames; ++f) {
        const auto i = static_cast<std::size_t>(f);
        EXPECT_TRUE(identicalImages(lanes.images[i], general.images[i])) << name << " frame " << f;
        const RayCounts& a = lanes.stats[i].rays;
        const RayCounts& b = general.stats[i].rays;
        EXPECT_EQ(a.primary, b.primary) << name;
        EXPECT_EQ(a.shadow, b.shadow) << name << " frame " << f;
        EXPECT_EQ(a.reflection, b.reflection) << name << " frame " << f;
        EXPECT_EQ(a.refraction, b.refraction) << name << " frame " << f;
        ASSERT_EQ(lanes.stats[i].cache.has_value(), general.stats[i].cache.has_value());
        if (lanes.stats[i].cache) {
            // The lanes look CCT rays up as they spawn them
            // (RayCache::lookupAddressed), the general path in batches.
            EXPECT_EQ(lanes.stats[i].cache->lookups(), general.stats[i].cache->lookups()) << name << " frame " << f;
            EXPECT_EQ(lanes.stats[i].cache->hits(), general.stats[i].cache->hits()) << name << " frame " << f;
            EXPECT_EQ(lanes.stats[i].cache->misses(), general.stats[i].cache->misses()) << name << " frame " << f;
            for (std::size_t o = 0; o < lanes.stats[i].cache->objects.size(); ++o)
                EXPECT_EQ(lanes.stats[i].cache->objects[o].hitsByLevel, general.stats[i].cache->objects[o].hitsByLevel)
                    << name << " frame " << f << " cube " << o;
            EXPECT_EQ(lanes.stats[i].cache->stores(), general.stats[i].cache->stores()) << name << " frame " << f;
        }
    }
}

}  // namespace

TEST(WaveLanes, EveryBuiltinSceneUncachedEqualsTheGeneralPath) {
    for (const BuiltinSceneInfo& info : builtinScenes()) {
        const auto scene = makeBuiltinScene(info.name);
        ASSERT_TRUE(scene.has_value()) << info.name;
        expectLanesEqualGeneralPath(*scene, info.name, CacheTechnique::None, 1);
    }
}

TEST(WaveLanes, CachedFramesEqualTheGeneralPath) {
    // The second frame of each answers from the cubes the first filled;
    // the animated ones also drop what moved.
    for (const char* name : {"room", "glass", "bowl", "grid-8", "orbit", "room-moving"}) {
        const auto scene = makeBuiltinScene(name);
        ASSERT_TRUE(scene.has_value()) << name;
        expectLanesEqualGeneralPath(*scene, name, CacheTechnique::Cct, 3);
        expectLanesEqualGeneralPath(*scene, name, CacheTechnique::Cdct, 2);
    }
}

TEST(WaveLanes, IdealCacheFramesEqualTheGeneralPath) {
    // An ideal cache answers its misses black (core_speed's ideal frame).
    for (const char* name : {"grid-8", "glass"}) {
        const auto scene = makeBuiltinScene(name);
        ASSERT_TRUE(scene.has_value()) << name;
        expectLanesEqualGeneralPath(*scene, name, CacheTechnique::Cct, 2, PipelineKind::Ray, true);
    }
}

TEST(WaveLanes, HybridPipelineEqualsTheGeneralPath) {
    // First hits from a G-buffer (made of primary-ray packets, so the test
    // needs no OpenGL): their surfaces come in, shading starts at the shadow rays.
    for (const char* name : {"room", "glass", "behind-8", "shapes", "orbit"}) {
        const auto scene = makeBuiltinScene(name);
        ASSERT_TRUE(scene.has_value()) << name;
        expectLanesEqualGeneralPath(*scene, name, CacheTechnique::None, 1, PipelineKind::Hybrid);
        expectLanesEqualGeneralPath(*scene, name, CacheTechnique::Cct, 2, PipelineKind::Hybrid);
    }
}

TEST(WaveLanes, TexturedSpheresEqualTheGeneralPath) {
    // No built-in scene has a textured sphere: their texture coordinates
    // are computed one lane at a time.
    auto scene = makeBuiltinScene("room");
    ASSERT_TRUE(scene.has_value());
    int textured = 0;
    for (SceneObject& object : scene->objects)
        if (std::holds_alternative<Sphere>(object.shape) && !object.material.reflects() &&
            !object.material.refracts()) {
            object.material.diffuseTexture = Texture::checkerboard({Rgb{0.9f, 0.2f, 0.1f}, Rgb{0.1f}, 8.0f});
            object.material.specular = Rgb{0.5f};
            object.material.shininess = 7.5f;  // not a whole exponent: std::pow, lane by lane
            ++textured;
        }
    ASSERT_GT(textured, 0);
    expectLanesEqualGeneralPath(*scene, "room with textured spheres", CacheTechnique::None, 1);
}

TEST(WaveLanes, RealMeshScenesEqualTheGeneralPath) {
    for (const char* name : {"bunny-glass", "teapot-mirrors"}) {
        const std::optional<Scene> scene = makeRealMeshScene(name, builtMeshSearchPath());
        if (!scene) {
            RAYCACHE_SKIP_OR_FAIL_IN_CI(std::string(name) + " needs the built meshes (scripts/install-deps.sh)");
        }
        expectLanesEqualGeneralPath(*scene, name, CacheTechnique::None, 1);
        expectLanesEqualGeneralPath(*scene, name, CacheTechnique::Cct, 2);
    }
}
