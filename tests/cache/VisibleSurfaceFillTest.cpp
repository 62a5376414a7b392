// Caching cubes filled from what the camera sees (render/VisibleSurfaceFill.h,
// RayCacheSettings::visibleFill), against the uncached tracer: every filled
// texel keeps the record of its visibility ray (invalidation-oracle mode), and
// that ray traced again without caches must bring back the stored colour
// within rounding where the fill is exact. Also: the first frame is the
// uncached image, and images and cubes do not depend on the thread count.
#include <gtest/gtest.h>

#include "PathRender.h"

#include <cstdio>

#include "scene/BuiltinScenes.h"
#include "session/InvalidationOracle.h"
#include "session/RenderSession.h"

using namespace raycache;

namespace {

struct OracleRun {
    std::size_t texels = 0;             // valid after one frame
    std::int64_t differing = 0;         // re-traced colour not bit-identical
    std::int64_t beyondTolerance = 0;   // re-traced colour off by more than InvalidationCounts::kTolerance
    std::uint64_t fillRays = 0;
};

// One frame of room at 160×120 with CCT cubes of 64² and the oracle's
// records, then every valid texel's ray traced again.
OracleRun oracleFrame(VisibleFill fill) {
    const Scene scene = *makeBuiltinScene("room");
    RenderSettings settings;
    settings.width = 160;
    settings.height = 120;
    settings.threads = 2;
    settings.cache.techniqueOverride = CacheTechnique::Cct;
    settings.cache.resolutionOverride = 64;
    settings.cache.invalidationOracle = true;
    settings.cache.visibleFill = fill;
    RenderSession session(scene, settings);
    Image film;
    const FrameStats stats = session.render(scene.camera, film);
    InvalidationOracle oracle;
    oracle.take(session);
    return {oracle.texelCount(), oracle.differing(), oracle.differingBeyondTolerance(), stats.rays.fill};
}

}  // namespace

TEST(VisibleSurfaceFill, ExactFillStoresWhatItsRayBringsBack) {
    const OracleRun traced = oracleFrame(VisibleFill::Off);
    const OracleRun filled = oracleFrame(VisibleFill::Exact);
    std::printf("[fill] room: %zu texels traced only, %zu with the exact fill (%llu visibility rays); "
                "%lld differ from their ray's uncached colour, %lld beyond tolerance\n",
                traced.texels, filled.texels, static_cast<unsigned long long>(filled.fillRays),
                static_cast<long long>(filled.differing), static_cast<long long>(filled.beyondTolerance));
    EXPECT_EQ(traced.differing, 0);  // without the fill every texel is its own ray's colour, bit for bit
    EXPECT_EQ(traced.fillRays, 0u);
    EXPECT_GT(filled.fillRays, 0u);
    // The fill added texels the camera's reflected rays did not reach.
    EXPECT_GT(filled.texels, traced.texels + 100);
    // Hit points found from another ray differ in their last bits; nothing more.
    EXPECT_EQ(filled.beyondTolerance, 0) << filled.differing << " of " << filled.texels << " texels differ";
}

TEST(VisibleSurfaceFill, ApproximateFillStoresTheCamerasHighlights) {
    // room's diffuse objects have highlights: seen from the mirror they are
    // elsewhere, so some filled texels are off by more than rounding. (This
    // is what the exact fill leaves out.)
    const OracleRun approximate = oracleFrame(VisibleFill::Approximate);
    const OracleRun exact = oracleFrame(VisibleFill::Exact);
    std::printf("[fill] room, approximate: %zu texels, %lld beyond tolerance\n", approximate.texels,
                static_cast<long long>(approximate.beyondTolerance));
    EXPECT_GT(approximate.texels, exact.texels);
    EXPECT_GT(approximate.beyondTolerance, 0);
}

TEST(VisibleSurfaceFill, FirstFrameEqualsTheUncachedRender) {
    const PathRender filled = renderPath("room", CacheTechnique::Cct, 1, true, 96, 2, 64, nullptr,
                                         TileBalance::Dynamic, 1, 0, false, VisibleFill::Exact);
    const PathRender plain = renderPath("room", CacheTechnique::None, 1, true, 96);
    ASSERT_EQ(filled.frames.size(), 1u);
    EXPECT_GT(filled.stats[0].rays.fill, 0u);
    EXPECT_EQ(filled.frames[0].pixels(), plain.frames[0].pixels());
}

TEST(VisibleSurfaceFill, ImagesAndCubesBitIdenticalAcrossThreadCounts) {
    for (const char* scene : {"room", "grid-8"}) {
        const PathRender one = renderPath(scene, CacheTechnique::Cct, 3, false, 96, 1, 64, nullptr,
                                          TileBalance::Dynamic, 1, 0, true, VisibleFill::Exact);
        for (const int threads : {2, 3}) {
            const PathRender many = renderPath(scene, CacheTechnique::Cct, 3, false, 96, threads, 64, nullptr,
                                               TileBalance::Dynamic, 1, 0, true, VisibleFill::Exact);
            ASSERT_EQ(one.frames.size(), many.frames.size());
            for (std::size_t f = 0; f < one.frames.size(); ++f)
                EXPECT_EQ(one.frames[f].pixels(), many.frames[f].pixels())
                    << scene << ", frame " << f << ", " << threads << " threads";
            EXPECT_EQ(one.texels, many.texels) << scene << ", " << threads << " threads";
        }
    }
}
