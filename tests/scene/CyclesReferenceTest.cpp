// glTF scenes made and exported by Blender, against Cycles' renders of them
// (tests/data/blender/README.md: how they were made, the Cycles settings,
// the references' noise and aliasing). Cycles is the external oracle here,
// as POV-Ray is for the classic scenes: each scene rendered with no option
// given, one ray a pixel, must stay within a margin of the PSNR and SSIM it
// reaches today (scripts/compare-with-cycles.sh prints them); `studio`, the
// scene users reported, must reach 25 dB and SSIM 0.9.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "metrics/ImageMetrics.h"
#include "metrics/Ssim.h"
#include "scene/GltfScene.h"
#include "scene/ImageLoader.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

const std::filesystem::path kBlenderData = std::filesystem::path(RAYCACHE_TEST_DATA_DIR) / "blender";

struct Expected {
    const char* scene;
    double minPsnr;
    double minSsim;
};

// Today's figures less about 1.5 dB and 0.02: a shading change that costs
// more than that against Cycles fails here.
constexpr Expected kExpected[] = {
    {"lambert-point", 51.0, 0.99}, {"lambert-sun", 33.5, 0.97}, {"lambert-spot", 27.0, 0.91},
    {"studio", 25.0, 0.90},        {"metals", 25.0, 0.91},      {"glass", 31.3, 0.945},
    {"textured", 26.0, 0.89},
};

}  // namespace

TEST(CyclesReference, BlenderScenesRenderCloseToCycles) {
    for (const Expected& e : kExpected) {
        const Image reference = loadImageFile(kBlenderData / (std::string(e.scene) + ".png"));
        const Scene scene = loadGltfScene(kBlenderData / (std::string(e.scene) + ".glb"));
        RenderSettings settings;
        settings.width = reference.width();
        settings.height = reference.height();
        settings.threads = 2;
        Image film;
        RenderSession(scene, settings).render(scene.camera, film);
        const double p = psnr(film, reference), s = ssim(film, reference);
        std::printf("[ %s ] PSNR %.2f dB, SSIM %.4f against Cycles\n", e.scene, p, s);
        EXPECT_GE(p, e.minPsnr) << e.scene;
        EXPECT_GE(s, e.minSsim) << e.scene;
    }
}

// Caching is unchanged in meaning under glTF's BRDF and physical lights:
// the cubes of the chrome ball, the glass Suzanne and the glass sphere and
// slab cache what their rays bring back, the Fresnel and BRDF weights apply
// at the parent, and a filled CCT frame stays close to the uncached render.
TEST(CyclesReference, CctOnBlenderScenesStaysCloseToUncached) {
    for (const char* name : {"studio", "glass"}) {
        const Scene scene = loadGltfScene(kBlenderData / (std::string(name) + ".glb"));
        RenderSettings settings;
        settings.width = 320;
        settings.height = 240;
        settings.threads = 2;
        settings.cache.techniqueOverride = CacheTechnique::None;
        Image uncached;
        RenderSession(scene, settings).render(scene.camera, uncached);
        settings.cache.techniqueOverride = CacheTechnique::Cct;
        settings.cache.resolutionOverride = 512;
        RenderSession cached(scene, settings);
        Image film;
        FrameStats last;
        for (int frame = 0; frame < 3; ++frame) last = cached.render(scene.camera, film);
        ASSERT_TRUE(last.cache.has_value()) << name;
        EXPECT_GT(last.cache->hits(), 0u) << name << ": the filled cubes answer";
        const double db = psnr(film, uncached);
        std::printf("[ %s ] CCT filled against uncached: %.2f dB, %llu hits\n", name, db,
                    static_cast<unsigned long long>(last.cache->hits()));
        EXPECT_GE(db, 35.0) << name;
    }
}
